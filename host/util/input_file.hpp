#pragma once
// Opening an input file with an error that says what is wrong: a directory is "is a
// directory" (an ifstream opens one and then reads nothing, which read as "empty input"),
// anything else that cannot be read gives the system's reason.
#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace collide::util {

struct InputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Throws InputError "<path>: is a directory, expected a file" or "<path>: cannot open: <why>".
std::ifstream openInput(const std::filesystem::path& path);

}  // namespace collide::util
