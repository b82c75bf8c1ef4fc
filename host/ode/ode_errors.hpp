#pragma once
// ODE's error, debug and message handlers. By default ODE prints "ODE INTERNAL ERROR" and
// aborts the process (SIGABRT) on any failed assertion or bad argument, which leaves the
// user a core dump and an empty output file. Our handlers turn errors and failed
// assertions into an OdeError exception with ODE's message, and print ODE's warnings.
//
// Inputs are validated before they reach ODE (batch/sane_ranges.hpp); these handlers are for
// what still slips through. An ODE error raised while another exception is already
// unwinding (ODE objects destroyed in a state ODE refuses) cannot be thrown: the message is
// printed and the process exits with status 1 instead of aborting.
#include <stdexcept>

namespace collide::ode {

struct OdeError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Idempotent; ode::Library's constructor calls it, so every user of ODE has them.
void installErrorHandlers();

}  // namespace collide::ode
