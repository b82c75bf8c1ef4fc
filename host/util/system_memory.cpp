#include "util/system_memory.hpp"

#include <fstream>
#include <sstream>
#include <string>

namespace collide::util {

std::optional<std::uint64_t> availableMemoryBytes() {
  std::ifstream in("/proc/meminfo");
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("MemAvailable:", 0) != 0) continue;
    std::istringstream f(line.substr(13));
    std::uint64_t kb = 0;
    std::string unit;
    if (f >> kb >> unit && unit == "kB") return kb * 1024;
    return std::nullopt;
  }
  return std::nullopt;
}

}  // namespace collide::util
