#pragma once
// RAII for ODE's process-wide initialisation. dInitODE2/dCloseODE are reference
// counted by ODE 0.16 itself (checked with Debian's libode8: init, init, close leaves
// ODE usable), so every owner of ODE objects can hold one of these. It also installs our
// error handlers (ode_errors.hpp): ODE's own abort the process.
#include <ode/ode.h>

#include "ode/ode_errors.hpp"

namespace collide::ode {

class Library {
 public:
  Library() {
    installErrorHandlers();
    dInitODE2(0);
  }
  ~Library() { dCloseODE(); }
  Library(const Library&) = delete;
  Library& operator=(const Library&) = delete;
};

}  // namespace collide::ode
