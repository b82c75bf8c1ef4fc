#pragma once
// What this machine can still give a process: the kernel's estimate of memory available
// without swapping (MemAvailable in /proc/meminfo).
#include <cstdint>
#include <optional>

namespace collide::util {

// Bytes, or nothing where the kernel does not say (not Linux, an old kernel).
std::optional<std::uint64_t> availableMemoryBytes();

}  // namespace collide::util
