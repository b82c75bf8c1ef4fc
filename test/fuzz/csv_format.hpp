#pragma once
// The CSV targets parse into each link format: the input's first byte picks which, so the
// fuzzer explores every format's overflow and rounding paths with one corpus.
#include <cstddef>
#include <cstdint>

#include "format/link_format.hpp"

namespace collide::fuzz {

inline LinkFormat pickFormat(const std::uint8_t*& data, std::size_t& size) {
  if (size == 0) return LinkFormat::Binary32;
  const auto f = static_cast<LinkFormat>(data[0] % 4);
  ++data;
  --size;
  return f;
}

}  // namespace collide::fuzz
