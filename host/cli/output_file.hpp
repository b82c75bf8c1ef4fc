#pragma once
// Every file the CLI writes goes through OutputFile, so that no write error passes
// silently and no failure leaves a truncated file that looks valid:
// - a regular file (new or old) is written to a temporary file in the same folder and
//   renamed into place by commit(), after every write, the flush and the close succeeded;
// - on any failure, or if the OutputFile is destroyed without commit() (an exception on
//   the way), the temporary is removed and an old file at the path is left as it was;
// - "-" (only where the caller allows it) is stdout, and a path that exists but is not a
//   regular file (/dev/null, /dev/full, a FIFO) is written in place: a rename would
//   replace the device or pipe itself. Both are still checked write by write.
// Errors are OutputError "<path>: <what failed>: <strerror>".
#include <memory>
#include <ostream>
#include <stdexcept>
#include <string>

namespace collide::cli {

struct OutputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

class OutputFile {
 public:
  enum class Dash { IsFileName, IsStdout };
  explicit OutputFile(std::string path, Dash dash = Dash::IsFileName);
  ~OutputFile();
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  // Write here. A failed write sets the stream's badbit and remembers why; commit() reports it.
  std::ostream& stream() { return *os_; }
  // Flush, close and rename into place; throws OutputError naming the file on any failure
  // (the temporary is then removed, an old file kept).
  void commit();
  const std::string& path() const { return path_; }

 private:
  class FdBuf;
  [[noreturn]] void fail(const std::string& what, int err, const std::string& note = "");
  void discard() noexcept;

  std::string path_;    // as given, for messages
  std::string target_;  // what commit() renames onto (a symlink's target)
  std::string temp_;    // "" when writing in place
  std::unique_ptr<FdBuf> buf_;
  std::unique_ptr<std::ostream> os_;
  bool done_ = false;
};

}  // namespace collide::cli
