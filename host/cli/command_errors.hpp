#pragma once
// The exit codes of every `collide` subcommand (commands.hpp): 0 ok, 1 an error, 2 what
// this build cannot do (an AFU it lacks, world mode on the AFU). One place maps them.
#include <exception>
#include <iostream>

#include "driver/afu_factory.hpp"

namespace collide::cli {

// Runs body (which returns the exit code), and turns what it throws into a message on
// stderr prefixed with `command` and the matching exit code.
template <typename F>
int reportErrors(const char* command, F&& body) {
  try {
    return body();
  } catch (const driver::AfuUnavailable& e) {
    std::cerr << command << ": " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << command << ": " << e.what() << "\n";
    return 1;
  }
}

}  // namespace collide::cli
