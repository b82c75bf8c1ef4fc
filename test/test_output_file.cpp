// OutputFile: a file replaces the old one only when every write, the flush and the close
// succeeded; a failure names the file, removes the temporary and keeps the old file.
#include <gtest/gtest.h>

#include <filesystem>
#include <functional>
#include <fstream>
#include <sstream>
#include <unistd.h>

#include "cli/output_file.hpp"

using collide::cli::OutputError;
using collide::cli::OutputFile;
namespace fs = std::filesystem;

namespace {
struct TempDir {
  fs::path dir;
  TempDir() {
    std::string t = (fs::temp_directory_path() / "collide-output-XXXXXX").string();
    dir = ::mkdtemp(t.data());
  }
  ~TempDir() { fs::remove_all(dir); }
  std::size_t entries() const { return static_cast<std::size_t>(std::distance(fs::directory_iterator(dir), {})); }
};
std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}
void spit(const fs::path& p, const std::string& text) { std::ofstream(p) << text; }
std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const OutputError& e) {
    return e.what();
  }
  return "(no error)";
}
}  // namespace

TEST(OutputFile, CommitReplacesTheOldFileAndLeavesNoTemporary) {
  TempDir t;
  const fs::path p = t.dir / "out.csv";
  spit(p, "old\n");
  {
    OutputFile f(p.string());
    f.stream() << "new\n";
    EXPECT_EQ(slurp(p), "old\n");  // nothing replaced before commit
    f.commit();
  }
  EXPECT_EQ(slurp(p), "new\n");
  EXPECT_EQ(t.entries(), 1u);
}

TEST(OutputFile, AnAbandonedWriteKeepsTheOldFile) {
  TempDir t;
  const fs::path p = t.dir / "out.csv";
  spit(p, "old\n");
  try {
    OutputFile f(p.string());
    f.stream() << std::string(1 << 20, 'x');  // past the buffer: on disk, in the temporary
    throw std::runtime_error("the run failed half-way");
  } catch (const std::runtime_error&) {
  }
  EXPECT_EQ(slurp(p), "old\n");
  EXPECT_EQ(t.entries(), 1u);  // the temporary is gone
}

TEST(OutputFile, AFullDeviceFailsNamingTheFile) {
  if (!fs::exists("/dev/full")) GTEST_SKIP() << "no /dev/full on this machine";
  const std::string e = errorOf([] {
    OutputFile f("/dev/full");
    f.stream() << "a row\n";
    f.commit();
  });
  EXPECT_NE(e.find("/dev/full: write failed: No space left on device"), std::string::npos) << e;
}

TEST(OutputFile, BadPathsFailNamingTheFile) {
  TempDir t;
  EXPECT_NE(errorOf([&] { OutputFile f(t.dir.string()); }).find(t.dir.string() + ": is a directory"),
            std::string::npos);
  const std::string missing = (t.dir / "no" / "such.csv").string();
  EXPECT_NE(errorOf([&] { OutputFile f(missing); }).find(missing + ": cannot create a temporary file"),
            std::string::npos);
}

TEST(OutputFile, ASymlinkKeepsPointingAtTheNewContent) {
  TempDir t;
  spit(t.dir / "real.csv", "old\n");
  fs::create_symlink("real.csv", t.dir / "link.csv");
  OutputFile f((t.dir / "link.csv").string());
  f.stream() << "new\n";
  f.commit();
  EXPECT_TRUE(fs::is_symlink(t.dir / "link.csv"));
  EXPECT_EQ(slurp(t.dir / "real.csv"), "new\n");
}
