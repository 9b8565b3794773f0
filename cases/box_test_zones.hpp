// Where the bed moves under the sleeper (Lu & McDowell 2007, Figs 15-17): the paper
// reads its displacement vectors as "spheres beside the sleeper rise, and keep rising
// on unloading; clumps beneath it move down, and back up a little on unloading".
// The zones (docs/BOX_TEST.md, "Zones") are the top layer of the bed at the start of
// loading, split at the sleeper's footprint:
//   beneath  centre x within [x0, x1], the footprint;
//   beside   centre x outside it, to the box's end walls on both sides.
#pragma once

#include "cases/box_test_result.hpp"

namespace ballast {

// From the run's per-body records (positions at the start of loading, at peak and
// after the cycle; rotations of each phase, deg). `surface`: the bed's top under the
// sleeper at the start of loading, m; `depth`: the top layer's depth, m.
Zones measure_zones(const BoxTestResult& r, double x0, double x1, double surface, double depth);

}  // namespace ballast
