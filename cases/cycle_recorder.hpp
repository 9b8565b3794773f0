// What a box test records for each load cycle (CycleRecords): the sleeper's settlement
// at each cycle's peak and end, the work the sleeper did on the bed, the bodies'
// mean rotation, how many particles carry the sleeper, and the porosity under it;
// full snapshots of the bed at the cycles the scene names. Many-cycle runs (10^5
// cycles) show how permanent settlement grows with the number of cycles N, roughly
// with log N for railway ballast: the paper (Lu & McDowell 2007) loads once and
// leaves this for later.
//
// The recorder is told after every step and acts only when a cycle's peak or end
// has passed, so the cheap measures cost nothing on the steps between.
#pragma once

#include <vector>

#include "cases/box_test_result.hpp"
#include "cases/box_test_scene.hpp"
#include "engine/simulation.hpp"

namespace ballast {

// The cycles whose end is snapshotted and whose load–deformation series is sampled:
// the scene's /measurement/snapshot_cycles, or by default the powers of ten up to
// the number of cycles and the last cycle (1, 10, 100 and 250 for 250 cycles).
std::vector<long> snapshot_cycles_of(const BoxTestScene& s);

// Least-squares slope of permanent settlement against log10 N over cycles 1..N,
// m per decade of cycles; 0 for fewer than two cycles.
double settlement_log_slope(const std::vector<double>& settlement_trough);

class CycleRecorder {
 public:
  CycleRecorder() = default;  // to be read from a checkpoint
  // Loading starts now (sim.time() = t0) with the sleeper `wall` (spanning x0..x1)
  // driven by servo `servo`.
  CycleRecorder(const BoxTestScene& s, const Simulation& sim, Index wall, Index servo, double x0,
                double x1);

  // After every step of the load cycles.
  void after_step(const Simulation& sim, CycleRecords& out);
  // Whether the cycle now running is one whose series is sampled.
  bool sampling_series() const {
    return next_snapshot_ < snapshots_.size() && snapshots_[next_snapshot_] == cycle_;
  }
  // The cycles completed so far.
  long cycles_done() const { return cycle_ - 1; }

  // Every field, for checkpoints (engine/state_io.hpp).
  template <class Io>
  void state_fields(Io& io) {
    io(wall_, servo_, x0_, x1_, width_, cube_side_, t0_, period_, z0_, cycle_, peak_passed_, work_,
       last_force_, last_settlement_, snapshots_, next_snapshot_);
  }

 private:
  double settlement(const Simulation& sim) const;
  void end_cycle(const Simulation& sim, CycleRecords& out);

  Index wall_ = 0, servo_ = 0;
  double x0_ = 0.0, x1_ = 0.0, width_ = 0.0, cube_side_ = 0.0;  // m: the column under the sleeper
  double t0_ = 0.0, period_ = 0.0, z0_ = 0.0;                   // s, s, m
  long cycle_ = 1;                                              // the cycle running now, 1-based
  bool peak_passed_ = false;
  double work_ = 0.0, last_force_ = 0.0, last_settlement_ = 0.0;  // J, N, m
  std::vector<long> snapshots_;
  std::size_t next_snapshot_ = 0;
};

}  // namespace ballast
