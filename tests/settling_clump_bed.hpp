// The small settling clump bed two tests share: 120 Table 2 Sample 1 clumps in a
// 300 × 150 mm box fall at 100 g and, with dashpots, come to rest within a few
// hundredths of a second, crossing many neighbour builds on the way.
#pragma once

#include "cases/bed.hpp"

namespace ballast {

inline BedOptions settling_clump_bed_options() {
  BedOptions o;
  o.count = 120;
  o.length = 0.3;
  o.width = 0.15;
  o.clumps = ClumpParams{};
  o.friction = 0.4;
  o.sim.damping_ratio = 0.1;
  o.sim.local_damping = 0.2;
  o.sim.gravity = Vec3(0, 0, -981.0);
  return o;
}

}  // namespace ballast
