#pragma once
// Host shared memory as the AFU sees it: an array of 64-byte lines addressed by line
// number. Buffers are carved out with a bump allocator; line 0 is never handed out so
// that a base address of 0 stays "not configured" (docs/afu-interface.md, error bit 4).
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

#include "afu_contract.hpp"

namespace collide::link {

// The generated AFU contract is the truth: the AFU moves lines of this size.
constexpr std::size_t kLineBytes = contract::LINE_BYTES;
using Line = std::array<std::uint8_t, kLineBytes>;

struct Buffer {
  std::uint64_t base = 0;   // line address
  std::uint64_t lines = 0;
};

class HostMemory {
 public:
  HostMemory() : lines_(1) {}  // line 0: reserved

  Buffer allocate(std::uint64_t lines);  // zero-filled
  void releaseAll() { lines_.resize(1); }
  std::uint64_t sizeLines() const { return lines_.size(); }

  bool contains(std::uint64_t addr) const { return addr != 0 && addr < lines_.size(); }
  const Line& line(std::uint64_t addr) const;  // throws std::out_of_range
  Line& line(std::uint64_t addr);

  // Little-endian scalar access at (line, byte offset).
  template <typename T>
  T load(std::uint64_t addr, std::size_t byte) const {
    T v;
    std::memcpy(&v, line(addr).data() + byte, sizeof(T));
    return v;
  }
  template <typename T>
  void store(std::uint64_t addr, std::size_t byte, T v) {
    std::memcpy(line(addr).data() + byte, &v, sizeof(T));
  }

 private:
  std::vector<Line> lines_;
};

}  // namespace collide::link
