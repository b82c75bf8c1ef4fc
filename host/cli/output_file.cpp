#include "cli/output_file.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <streambuf>
#include <vector>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace collide::cli {

// A stream buffer over a file descriptor that checks every write(2) and keeps the errno of
// the first failure (std::ofstream only says that something failed, not what).
class OutputFile::FdBuf : public std::streambuf {
 public:
  FdBuf(int fd, bool owned) : fd_(fd), owned_(owned), buf_(1 << 16) { setp(buf_.data(), buf_.data() + buf_.size()); }
  ~FdBuf() override {
    if (owned_ && fd_ >= 0) ::close(fd_);
  }
  int error() const { return err_; }
  // Flushes and (for an owned descriptor) closes; false with error() set on failure.
  bool finish() {
    if (sync() != 0) return false;
    if (owned_) {
      const int fd = fd_;
      fd_ = -1;
      if (::close(fd) != 0) return record(errno);
    }
    return err_ == 0;
  }

 protected:
  int_type overflow(int_type c) override {
    if (!drain()) return traits_type::eof();
    if (!traits_type::eq_int_type(c, traits_type::eof())) {
      *pptr() = traits_type::to_char_type(c);
      pbump(1);
    }
    return traits_type::not_eof(c);
  }
  int sync() override { return drain() ? 0 : -1; }

 private:
  bool record(int err) {
    if (err_ == 0) err_ = err ? err : EIO;
    return false;
  }
  bool drain() {
    if (err_ != 0) return false;
    const char* p = pbase();
    while (p < pptr()) {
      const ssize_t n = ::write(fd_, p, static_cast<std::size_t>(pptr() - p));
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) return record(n < 0 ? errno : EIO);
      p += n;
    }
    setp(buf_.data(), buf_.data() + buf_.size());
    return true;
  }

  int fd_;
  bool owned_;
  std::vector<char> buf_;
  int err_ = 0;
};

OutputFile::OutputFile(std::string path, Dash dash) : path_(std::move(path)), target_(path_) {
  namespace fs = std::filesystem;
  if (path_.empty()) throw OutputError("output file: empty name");
  int fd = -1;
  bool owned = true;
  if (path_ == "-" && dash == Dash::IsStdout) {
    std::cout.flush();  // what the program printed so far comes first
    path_ = "<stdout>";
    fd = STDOUT_FILENO;
    owned = false;
  } else {
    struct stat st{};
    if (::lstat(path_.c_str(), &st) == 0 && S_ISLNK(st.st_mode)) {
      // Replace the file the link points to, not the link.
      std::error_code ec;
      const fs::path real = fs::weakly_canonical(path_, ec);
      if (!ec) target_ = real.string();
    }
    const bool exists = ::stat(target_.c_str(), &st) == 0;
    if (exists && S_ISDIR(st.st_mode)) throw OutputError(path_ + ": is a directory, not a file to write");
    if (exists && !S_ISREG(st.st_mode)) {
      fd = ::open(target_.c_str(), O_WRONLY | O_TRUNC | O_CLOEXEC);
      if (fd < 0) {
        const int err = errno;
        fail("cannot open for writing", err);
      }
    } else {
      const fs::path t(target_);
      const fs::path dir = t.has_parent_path() ? t.parent_path() : fs::path(".");
      std::string tmpl = (dir / ("." + t.filename().string() + ".tmp.XXXXXX")).string();
      fd = ::mkstemp(tmpl.data());
      if (fd < 0) {
        const int err = errno;
        fail("cannot create a temporary file in " + dir.string(), err);
      }
      temp_ = tmpl;
      // mkstemp gives 0600; a rewritten file keeps its mode, a new one gets what open() would.
      mode_t mode;
      if (exists) {
        mode = st.st_mode & 07777;
      } else {
        const mode_t mask = ::umask(0);
        ::umask(mask);
        mode = 0666 & ~mask;
      }
      if (::fchmod(fd, mode) != 0) {
        const int err = errno;
        ::close(fd);
        fail("cannot set the mode of " + temp_, err);
      }
    }
  }
  buf_ = std::make_unique<FdBuf>(fd, owned);
  os_ = std::make_unique<std::ostream>(buf_.get());
}

OutputFile::~OutputFile() {
  if (!done_) discard();
}

void OutputFile::discard() noexcept {
  done_ = true;
  os_.reset();
  buf_.reset();  // closes the descriptor
  if (!temp_.empty()) ::unlink(temp_.c_str());
}

void OutputFile::fail(const std::string& what, int err, const std::string& note) {
  discard();
  throw OutputError(path_ + ": " + what + ": " + std::strerror(err ? err : EIO) + note);
}

void OutputFile::commit() {
  if (done_) throw std::logic_error("OutputFile::commit: " + path_ + " was already committed or discarded");
  const std::string kept = temp_.empty() ? "" : " (nothing replaced: an old file stays as it was)";
  os_->flush();
  if (!buf_->finish() || os_->bad()) fail("write failed", buf_->error(), kept);
  if (!temp_.empty() && std::rename(temp_.c_str(), target_.c_str()) != 0) {
    const int err = errno;
    fail("cannot rename " + temp_ + " into place", err, kept);
  }
  temp_.clear();
  done_ = true;
}

}  // namespace collide::cli
