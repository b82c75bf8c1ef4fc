#include "util/input_file.hpp"

#include <cerrno>
#include <cstring>

namespace collide::util {

std::ifstream openInput(const std::filesystem::path& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw InputError(path.string() + ": is a directory, expected a file");
  errno = 0;
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string() + ": cannot open: " + std::strerror(errno ? errno : ENOENT));
  return in;
}

}  // namespace collide::util
