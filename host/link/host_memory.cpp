#include "link/host_memory.hpp"

#include <stdexcept>
#include <string>

namespace collide::link {

static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__,
              "host memory images are little-endian (docs/afu-interface.md); load/store use memcpy");

Buffer HostMemory::allocate(std::uint64_t lines) {
  Buffer b{lines_.size(), lines};
  lines_.resize(lines_.size() + lines, Line{});
  return b;
}

const Line& HostMemory::line(std::uint64_t addr) const {
  if (!contains(addr))
    throw std::out_of_range("host memory: line address " + std::to_string(addr) +
                            " outside [1, " + std::to_string(lines_.size()) + ")");
  return lines_[addr];
}

Line& HostMemory::line(std::uint64_t addr) {
  return const_cast<Line&>(static_cast<const HostMemory*>(this)->line(addr));
}

}  // namespace collide::link
