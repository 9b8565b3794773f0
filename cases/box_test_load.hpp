// The box test itself (Lu & McDowell 2007, section 3): a prepared bed, a sleeper
// placed on its surface and brought to the preload by a servo, then sinusoidal load
// cycles (3 → 40 → 3 kN at 3 Hz by default), measuring what section 3.3 reports.
//
// The sleeper is a servo-controlled rigid wall (a solid block), not a dynamic body:
// the paper prescribes the force history, and a servo delivers exactly that force
// history without needing a sleeper mass or inertia that the paper does not give.
// Achieved against target force is part of the result.
#pragma once

#include <functional>
#include <iosfwd>

#include "cases/box_test_checkpoint.hpp"
#include "cases/box_test_result.hpp"
#include "cases/box_test_scene.hpp"

namespace ballast {

// Prepares (box_test_prepare.hpp) and loads; progress lines go to `log`. `at_end`,
// when given, sees the simulation after the last stage that ran (the bed after
// preparation, compaction or the load cycle: `ballast run --export-packing`).
// `plan` says where the load cycles write checkpoints and whether the run resumes
// from one (box_test_checkpoint.hpp); the result is the same bits either way.
BoxTestResult run_box_test(const BoxTestScene& scene, std::ostream* log,
                           const std::function<void(const Simulation&)>& at_end = {},
                           const CheckpointPlan& plan = {});

// Stage 4 on a prepared bed.
void load_box_test(const BoxTestScene& scene, Simulation& sim, BoxTestResult& out,
                   std::ostream* log);

}  // namespace ballast
