// The settling demo `ballast demo` runs (and `make run` until the study runner
// exists): spheres poured into the box test's box and compacted the paper's way —
// enhanced gravity with friction 0.3, gravity back to 9.81 m/s², friction raised
// to 0.5 — printing the diagnostics as it goes.
//
// Phases:
//   pour     enhanced gravity, contact dashpots, no local damping (PFC local damping
//            slows a free fall to 0.3 g, which makes pouring needlessly long); ends
//            when the kinetic energy is below 1e-3 of the work gravity has done;
//   compact  enhanced gravity, PFC local damping 0.7, no dashpots, mu 0.3;
//   relax    gravity back to 9.81 m/s²;
//   mu=0.5   friction raised to the loading value.
// The last three end when the unbalanced-force ratio drops below target_ratio.
#pragma once

#include <cstdint>
#include <iosfwd>

namespace ballast {

struct SettlingDemoOptions {
  int spheres = 1936;
  std::uint64_t seed = 1;
  double gravity_factor = 20.0;     // enhanced gravity during compaction, × 9.81 m/s²
  double pour_damping_ratio = 0.3;  // contact dashpots while pouring
  double target_ratio = 1e-2;       // unbalanced-force ratio that ends a phase
  double min_phase_time = 0.02;     // s, simulated, before a phase may end
  long max_steps_per_phase = 400000;
  long report_every = 10000;  // steps between table rows
  double dt_safety = 0.8;     // dt = dt_safety × critical estimate
};

struct SettlingDemoResult {
  long steps = 0;
  double time = 0.0;          // s, simulated
  double wall_seconds = 0.0;  // s, elapsed
  double unbalanced_ratio = 0.0;
  double bed_height = 0.0;  // m, top of the highest sphere
  long contacts = 0;
  double energy_balance_error = 0.0;  // |balance| / gravity work
};

SettlingDemoResult run_settling_demo(const SettlingDemoOptions& o, std::ostream& out);

}  // namespace ballast
