#include "cases/scene_bounds.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <string>

#include "engine/clump_generator.hpp"
#include "engine/contact_laws.hpp"
#include "engine/simulation.hpp"
#include "engine/timestep.hpp"

namespace ballast {

namespace {

std::string num(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", v);
  return text;
}

// A run may take at most this many timesteps (of the one-sphere estimate, which is at
// least a bed's timestep): 10^5 cycles of the paper's box test at 0.51 µs are 6.5e10 steps.
constexpr double kMaxSteps = 1e12;
// A load cycle sampled by fewer timesteps than this is not a sinusoid.
constexpr double kMinStepsPerCycle = 20.0;
// Porosity grid cubes in the column under the sleeper, at most: the grid is walked
// cube by cube (engine/porosity.cpp), so a grid of nanometre cubes would never end.
constexpr double kMaxCubes = 1e8;
// What a box test holds in memory, bytes: a fixed part (the program, its libraries,
// HDF5; 18.4 MB measured) and a part per ball (its stores, its neighbour candidates
// and their histories, the cell list, the snapshots; 0.72-0.96 kB measured once the
// bed has settled). Peak resident sizes of whole box tests, docs/ACCURACY.md, "The
// largest bed"; about 30 % to spare.
constexpr double kFixedBytes = 24e6;
constexpr double kBytesPerBall = 1250.0;

// Memory the machine can give a new run now, bytes (MemAvailable of /proc/meminfo);
// 0 where it cannot be read (no check then).
double available_memory() {
  std::ifstream in("/proc/meminfo");
  std::string key;
  double kib = 0.0;
  while (in >> key) {
    if (key == "MemAvailable:" && in >> kib) return 1024.0 * kib;
    in.ignore(std::numeric_limits<std::streamsize>::max(), '\n');
  }
  return 0.0;
}

// The bed the run would build fits in the memory free now: a bed too large is refused
// before anything is computed, not met by the kernel's out-of-memory killer hours in.
void check_memory(const BoxTestScene& s) {
  const double have = available_memory();
  if (have <= 0.0) return;
  const double balls_per_particle = s.clumps ? expected_ball_count(*s.clumps) : 1.0;
  const double need = kFixedBytes + kBytesPerBall * balls_per_particle * double(s.count);
  const double most = std::floor((have - kFixedBytes) / (kBytesPerBall * balls_per_particle));
  const double gib = 1024.0 * 1024.0 * 1024.0;
  require_setup(need <= have, "/particles/count", s.count,
                "at most " + num(std::max(0.0, most)) + " particles (" + num(balls_per_particle) +
                    (s.clumps ? " balls each on average" : " ball each") +
                    ") on this machine: they would need about " + num(need / gib) + " GiB, and " +
                    num(have / gib) + " GiB is available");
}

}  // namespace

// A count that fills the floor at least one diameter deep, loose, and at most 1.8 box
// heights (generate_sample in box_test_prepare.cpp checks the latter again with the
// clumps' own volume, never below the sphere's used here).
void check_generated_bed(const BoxTestScene& s) {
  const double d = s.diameter;
  const double smallest = std::min({s.length, s.width, s.height});
  require_setup(d < smallest, "/particles/diameter", d,
                "< the box's smallest side, " + num(smallest) + " m");
  const double solid = s.count * kPi * d * d * d / 6.0;
  const double floor_area = s.length * s.width;
  const double depth = solid / ((1.0 - s.initial_porosity) * floor_area);
  require_setup(depth >= d, "/box/length x /box/width", floor_area,
                "a floor that /particles/count = " + std::to_string(s.count) +
                    " fills at least one diameter deep at the initial porosity: at most " +
                    num(solid / ((1.0 - s.initial_porosity) * d)) + " m^2");
  require_setup(depth <= 1.8 * s.height, "/particles/count", s.count,
                "few enough to fill at most 1.8 box heights at the initial porosity (needs " +
                    num(depth) + " m, box height " + num(s.height) + " m)");
  if (s.clumps)
    require_setup(s.clumps->d3 <= largest_d3(*s.clumps), "/particles/clump/d3", s.clumps->d3,
                  "<= " + num(largest_d3(*s.clumps)) + " with balls_per_direction = " +
                      std::to_string(s.clumps->balls_per_direction) +
                      " (the central ball at least min_radius_fraction of the virtual sphere)");
  check_memory(s);
}

void check_loading_bounds(const BoxTestScene& s, bool generated) {
  const SimulationSettings defaults;
  const int law = contact_law_index(s.sim.contact_law);
  const double r = 0.5 * s.diameter;
  // The whole peak load on one ball-sleeper contact: beyond an overlap of a ball's
  // radius the contact law describes nothing physical.
  const double carried = with_contact_law(law, [&](auto l) {
    using Law = decltype(l);
    const PairProperties pair = Law::mix(s.ball, s.wall);
    // overlap_at is monotonic in the force: bisect for the force at overlap r.
    double lo = 0.0, hi = 1.0;
    while (Law::overlap_at(pair, r, hi) < r && hi < 1e300) hi *= 2.0;
    for (int i = 0; i < 200 && hi - lo > 1e-9 * hi; ++i) {
      const double mid = 0.5 * (lo + hi);
      (Law::overlap_at(pair, r, mid) < r ? lo : hi) = mid;
    }
    return lo;
  });
  require_setup(s.peak_load <= carried, "/sleeper/peak_load", s.peak_load,
                "at most " + num(carried) + " N, the force one ball-sleeper contact carries " +
                    "at an overlap of a ball's radius");
  require_setup(
      s.sleeper_max_speed <= defaults.max_speed, "/sleeper/max_speed", s.sleeper_max_speed,
      "in (0, " + num(defaults.max_speed) + "] m/s: faster is what the engine takes for a blow-up");
  if (!generated) return;

  const double dt_one =
      lone_sphere_timestep(s.ball, r, s.simulated_density(), law, defaults.max_speed);
  require_setup(std::isfinite(dt_one) && dt_one > 0.0,
                "/materials/density and the ball's stiffness (ball_stiffness, ball_kn, ball_ks)",
                num(s.density) + " kg/m^3, " + num(s.ball.kn) + " and " + num(s.ball.ks) + " N/m",
                "values that give a finite positive timestep; these give " + num(dt_one) + " s");
  const double dt = s.sim.fixed_dt ? *s.sim.fixed_dt : s.sim.dt_safety * dt_one;
  const double period = 1.0 / s.frequency;
  require_setup(period >= kMinStepsPerCycle * dt, "/sleeper/frequency", s.frequency,
                "at most " + num(1.0 / (kMinStepsPerCycle * dt)) + " Hz, so that a cycle spans " +
                    "at least " + num(kMinStepsPerCycle) + " timesteps of about " + num(dt) + " s");
  const double steps = double(s.cycles) * period / dt;
  require_setup(steps <= kMaxSteps, "/sleeper/cycles", s.cycles,
                "cycles that take at most " + num(kMaxSteps) + " timesteps; these need about " +
                    num(steps) + " of " + num(dt) + " s (from /materials/density, the ball's " +
                    "stiffness and /numerics)");
}

void check_measurement_bounds(const BoxTestScene& s) {
  const double across = std::min(s.sleeper_length, s.width);
  require_setup(s.cube_side <= across, "/measurement/cube_side", s.cube_side,
                "at most " + num(across) + " m, so that the column under the sleeper holds a cube");
  // The column reaches the bed's top: for a generated bed at most the depth its count
  // fills at the initial porosity (it only compacts from there), else the box height.
  double column = s.height;
  if (s.packing_file.empty()) {
    const double solid = s.count * kPi * s.diameter * s.diameter * s.diameter / 6.0;
    column = std::min(column, solid / ((1.0 - s.initial_porosity) * s.length * s.width));
  }
  const double smallest = std::cbrt(s.sleeper_length * s.width * column / kMaxCubes);
  require_setup(s.cube_side >= smallest, "/measurement/cube_side", s.cube_side,
                "at least " + num(smallest) + " m, so that the column under the sleeper, " +
                    num(column) + " m high at most, holds at most " + num(kMaxCubes) + " cubes");
  require_setup(s.zone_depth <= s.height, "/measurement/zone_depth", s.zone_depth,
                "at most the box height, " + num(s.height) + " m");
}

}  // namespace ballast
