// Errors the engine raises. Set-up mistakes throw SetupError (std::invalid_argument)
// with a message naming the field, the value and what is allowed. A run that goes
// non-finite or explodes throws SimulationError naming the step, body and quantity;
// the Simulation object stays intact so diagnostics and output already written survive.
#pragma once

#include <sstream>
#include <stdexcept>
#include <string>

namespace ballast {

struct SetupError : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

struct SimulationError : std::runtime_error {
  SimulationError(long step, long body, const std::string& quantity, const std::string& what)
      : std::runtime_error(what), step(step), body(body), quantity(quantity) {}
  long step;
  long body;  // -1 when the failure is not tied to one body (e.g. total energy)
  std::string quantity;
};

// require_setup(cond, "ball radius", r, "> 0") throws
// "invalid ball radius = -0.1 (allowed: > 0)".
template <class T>
void require_setup(bool ok, const std::string& field, const T& value, const std::string& allowed) {
  if (ok) return;
  std::ostringstream s;
  s << "invalid " << field << " = " << value << " (allowed: " << allowed << ")";
  throw SetupError(s.str());
}

}  // namespace ballast
