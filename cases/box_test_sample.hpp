// Stages 1-2 of the box test's preparation (box_test_prepare.hpp), and what every
// stage shares: internal to cases/, between box_test_prepare.cpp, which runs the
// preparation, and box_test_sample.cpp, which makes the sample it starts from.
#pragma once

#include <chrono>
#include <iosfwd>

#include "cases/box_test_prepare.hpp"
#include "cases/box_test_scene.hpp"

namespace ballast {

// Stages 1-2 (box_test_sample.cpp): spheres generated at a reduced radius in the
// closed box and grown to full size, then, for a clump sample, each replaced by a
// clump grown back from inside its sphere; the lid stays on at the fill height, the
// bed frictionless and at rest.
PreparedBed generate_sample(const BoxTestScene& s, std::ostream* log);

// An imported packing (BoxTestScene::packing_file) in place of stages 1-2: the box
// with a lid just above the bed's top, frictionless, its bodies numbered cell by
// cell where that pays.
PreparedBed import_sample(const BoxTestScene& s, std::ostream* log);

// Wall-clock seconds since `since` (box_test_prepare.cpp).
double stage_seconds(std::chrono::steady_clock::time_point since);

// A stage's line in the run's log: steps, simulated and wall time, the unbalanced-
// force ratio and what ended the stage, contacts and coordination number; nothing
// when `log` is null (box_test_prepare.cpp).
void print_stage(std::ostream* log, const StageReport& r, const Simulation& sim);

}  // namespace ballast
