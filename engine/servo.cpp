#include "engine/servo.hpp"

#include <cmath>
#include <string>

#include "engine/errors.hpp"

namespace ballast {

std::function<double(double)> sinusoidal_load(double f_min, double f_max, double frequency,
                                              double t0) {
  const double mean = 0.5 * (f_max + f_min), amp = 0.5 * (f_max - f_min);
  const double omega = 2.0 * kPi * frequency;
  return [=](double t) { return mean - amp * std::cos(omega * (t - t0)); };
}

void validate_servo(const Servo& s, Index wall_count) {
  require_setup(!s.walls.empty(), "servo walls (count)", 0, ">= 1");
  for (Index w : s.walls)
    require_setup(w >= 0 && w < wall_count, "servo wall index", w,
                  "0.." + std::to_string(wall_count - 1));
  require_setup(std::abs(s.axis.norm() - 1.0) < 1e-9, "servo axis length", s.axis.norm(),
                "1 (a unit vector)");
  require_setup(static_cast<bool>(s.target_force), "servo target_force", "<empty>",
                "a function of time");
  require_setup(s.gain > 0.0 && s.gain <= 1.0, "servo gain", s.gain, "(0, 1]");
  require_setup(s.max_speed > 0.0, "servo max_speed", s.max_speed, "> 0 m/s");
}

}  // namespace ballast
