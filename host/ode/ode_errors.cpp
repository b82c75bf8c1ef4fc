#include "ode/ode_errors.hpp"

#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include <ode/ode.h>

namespace collide::ode {

namespace {

std::string format(const char* msg, va_list ap) {
  char buf[512];
  std::vsnprintf(buf, sizeof buf, msg, ap);
  return buf;
}

[[noreturn]] void raise(const char* kind, int num, const char* msg, va_list ap) {
  const std::string what = std::string("ODE ") + kind + " " + std::to_string(num) + ": " + format(msg, ap) +
                           " (an input reached ODE unchecked: please report it with the input)";
  static std::string first;  // the error being unwound, if it was ODE's
  if (std::uncaught_exceptions() > 0) {  // already unwinding: a second exception would terminate
    if (!first.empty()) std::fprintf(stderr, "collide: %s\n", first.c_str());
    std::fprintf(stderr, "collide: then, while cleaning up: %s\n", what.c_str());
    std::_Exit(1);
  }
  first = what;
  throw OdeError(what);
}

void onError(int num, const char* msg, va_list ap) { raise("error", num, msg, ap); }
void onDebug(int num, const char* msg, va_list ap) { raise("assertion", num, msg, ap); }
void onMessage(int num, const char* msg, va_list ap) {
  std::fprintf(stderr, "collide: ODE message %d: %s\n", num, format(msg, ap).c_str());
}

}  // namespace

void installErrorHandlers() {
  dSetErrorHandler(&onError);
  dSetDebugHandler(&onDebug);
  dSetMessageHandler(&onMessage);
}

}  // namespace collide::ode
