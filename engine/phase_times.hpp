// Where each thread's time goes in a step (Simulation::set_phase_timing): for the
// benchmark (`ballast bench-bed --phase-times`) and for anyone asking why two
// threads are not twice as fast as one. Off by default: on, a step reads the clock
// about five times per thread.
#pragma once

#include <array>
#include <vector>

namespace ballast {

struct PhaseTimes {
  // Per thread, seconds summed over the timed steps, and each step's five phases.
  struct Thread {
    double fork = 0.0;       // from the region's start until the thread is in it
    double contacts = 0.0;   // its share of the force pass
    double barrier = 0.0;    // waiting for the others after the force pass
    double integrate = 0.0;  // its share of the gather and leapfrog (the main thread:
                             // the walls first)
    double join = 0.0;       // from its end of the region until the region ends
    // The same five phases step by step (s, in the order above): a sum is dominated
    // by the few steps in which the host took a vCPU away for milliseconds, and a
    // median shows what the step costs when it does not (tests/bench/bed/phase_stats.hpp).
    std::vector<std::array<float, 5>> per_step;
  };
  std::vector<Thread> thread;
  double serial = 0.0;  // s, the step outside the parallel region (main thread)
  long steps = 0;
  std::vector<float> step_seconds;  // each timed step's wall time, s (4 bytes a step)
};

}  // namespace ballast
