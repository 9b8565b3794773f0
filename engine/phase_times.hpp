// Where each thread's time goes in a step (Simulation::set_phase_timing): for the
// benchmark (`ballast bench-bed --phase-times`) and for anyone asking why two
// threads are not twice as fast as one. Off by default: on, a step reads the clock
// about five times per thread.
#pragma once

#include <vector>

namespace ballast {

struct PhaseTimes {
  // Per thread, seconds summed over the timed steps.
  struct Thread {
    double fork = 0.0;       // from the region's start until the thread is in it
    double contacts = 0.0;   // its share of the force pass
    double barrier = 0.0;    // waiting for the others after the force pass
    double integrate = 0.0;  // its share of the gather and leapfrog (the main thread:
                             // the walls first)
    double join = 0.0;       // from its end of the region until the region ends
  };
  std::vector<Thread> thread;
  double serial = 0.0;  // s, the step outside the parallel region (main thread)
  long steps = 0;
};

}  // namespace ballast
