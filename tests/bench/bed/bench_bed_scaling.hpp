// `ballast bench-bed --scaling`: the speed-up from one thread to T, measured in one
// process on copies of the same bed stepped in alternating turns, beside what the
// host gives T independent copies in the same turns.
//
// Why not two runs one after the other: on a shared 2-vCPU host the speed of the
// machine drifts over seconds (the same binary's two-thread figure moved between
// 1.4e7 and 3.2e7 ball-steps/s within an hour, docs/PERFORMANCE.md), so two runs of a
// few seconds each, taken in turn, compare two different machines as often as two
// thread counts: per round, the sphere bed's speed-up ran from 1.39 to 2.09. Here
// the copies take turns every `chunk` steps (a fraction of a second), in the order
// one thread, T threads, T copies, then backwards, so that drift slower than a turn
// falls on all alike and a linear trend cancels over two turns.
//
// The T copies at once, one thread each (as a study runs its jobs), share no data
// and never wait for each other: their throughput over one copy's on one thread is
// the most T threads can give this bed on this host in these minutes (the host's
// other tenants, the vCPUs' shared core or memory, their clock), an upper bound for
// the speed-up that no splitting of the work can pass by more than cache effects.
//
// All copies run the same steps from the same state, so their end states must be
// bit-identical: the determinism across thread counts that the speed-up is quoted
// with is checked in the same run.
#pragma once

#include <vector>

#include "cases/bench_bed.hpp"
#include "cases/packing_file.hpp"
#include "tests/bench/bed/host_steal.hpp"

namespace ballast {

// The one-thread copy's times against another way of stepping, turn by turn.
struct TurnTimes {
  double seconds_one = 0.0, seconds_many = 0.0;  // summed over the turns, s
  // Per turn k: the one-thread time over the other for the same steps.
  std::vector<double> per_turn;
  void add(double one, double many);
  // Ratio of the summed times: the figure for the whole run.
  double ratio() const { return seconds_one / seconds_many; }
  // Quantile q in [0, 1] of per_turn (linear between order statistics).
  double quantile(double q) const;
};

struct ScalingRun {
  int threads = 2;  // T
  long steps = 0;   // per copy
  long chunk = 0;   // steps per turn
  // One copy on one thread against one copy on T threads: the speed-up.
  TurnTimes speedup;
  // One copy on one thread against T copies at once, one thread each, their time
  // divided by T: the throughput ratio, the host's bound.
  TurnTimes independent;
  // The hypervisor's steal (host_steal.hpp) during each way's turns: the one-thread
  // copy's, the T-thread copy's and the T copies'.
  StealMeter steal_one, steal_team, steal_copies;
  // state_hash after the last step: the one-thread copy, the T-thread copy, then
  // the T independent copies.
  std::vector<unsigned long long> hash;
  bool bit_identical() const;
};

// Builds the bed T + 2 times from `packing` with `options`, prepares them (not
// timed) and steps each `steps` steps in turns of `chunk`. Leaves the OpenMP thread
// count at `threads`.
ScalingRun interleaved_scaling(const Packing& packing, const BenchBedOptions& options, long steps,
                               long chunk, int threads);

}  // namespace ballast
