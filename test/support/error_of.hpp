#pragma once
// The message of the exception f() throws, or "(no error)": for tests that check what an
// error says (test only).
#include <exception>
#include <string>

namespace collide::test {

template <typename F>
std::string errorOf(F&& f) {
  try {
    f();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace collide::test
