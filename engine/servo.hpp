// Force-controlled walls (the sleeper), after PFC's and YADE's servo mechanism.
// Every step the servo measures the force the balls push back on its walls along
// its axis and sets the walls' common velocity
//     u = G·(F_target − F_measured),   G = gain / (K_walls·dt + C_walls),
// with K_walls the summed normal stiffness of the walls' active contacts and C_walls
// their summed normal dashpot coefficients (zero without contact dashpots): what
// the measured force changes by, per unit of u, at the next step. With gain = 1 the
// wall would remove the whole force error in one step if the bed were a set of
// independent springs; 0.5 (the default) halves it, which is stable; with dashpots
// the error obeys e' = (1 − gain)·e + gain·φ·e_prev, φ = C/(K·dt + C) < 1, whose
// roots lie inside the unit circle for every gain in (0, 1]. The
// speed is capped at max_speed so the wall cannot jump through the bed when it has
// no contacts yet.
#pragma once

#include <functional>
#include <vector>

#include "engine/types.hpp"

namespace ballast {

struct Servo {
  std::vector<Index> walls;                    // walls moved together (e.g. the sleeper)
  Vec3 axis = -Vec3::UnitZ();                  // unit direction the servo pushes along
  std::function<double(double)> target_force;  // N, as a function of time t (s)
  double gain = 0.5;                           // dimensionless, 0 < gain <= 1
  double max_speed = 0.1;                      // m/s

  // Last step, for reporting achieved against target.
  double measured_force = 0.0;  // N, reaction along -axis
  double target_now = 0.0;      // N
  double speed = 0.0;           // m/s along axis
};

// The sinusoidal sleeper load of the paper's box test: from f_min up to f_max and
// back at `frequency` Hz, starting at f_min when t = t0:
//   F(t) = (f_max + f_min)/2 − (f_max − f_min)/2 · cos(2π f (t − t0)).
// With 3 kN, 40 kN and 3 Hz this is 21.5 − 18.5·cos(6π t) kN.
std::function<double(double)> sinusoidal_load(double f_min, double f_max, double frequency,
                                              double t0);

void validate_servo(const Servo& s, Index wall_count);

}  // namespace ballast
