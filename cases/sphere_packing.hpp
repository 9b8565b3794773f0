// Initial sphere arrangements for scenes, tests and benchmarks.
#pragma once

#include <cstdint>
#include <vector>

#include "engine/types.hpp"

namespace ballast {

// `count` centres of non-overlapping spheres of radius r placed uniformly at random
// (random sequential addition) in the box [lo.x, hi.x] × [lo.y, hi.y] × [lo.z, top],
// where `top` is chosen so the spheres fill `volume_fraction` of that box. A loose
// random cloud (fraction ~0.3) falls into a random packing; a lattice would stack
// into columns. Centres come back in spatial order (grid cells, the slowest axis
// the one smallest_settled_section picks) for memory locality and a small boundary
// between the threads' shares. Deterministic for a given seed. Throws std::invalid_argument naming
// the count if the spheres cannot be placed below hi.z.
std::vector<Vec3> random_loose_packing(int count, double radius, const Vec3& lo, const Vec3& hi,
                                       double volume_fraction, std::uint64_t seed);

// The axis (0 x, 1 y, 2 z) across which a bed of `solid_volume` m³ of spheres,
// settled along −z in the box [lo, hi] at a packing fraction of 0.6, has its
// smallest section: the paper's 700 × 300 mm box with 1,936 ballast-sized spheres
// gives x (300 mm × 0.38 m against 700 × 300 mm).
int smallest_settled_section(double solid_volume, const Vec3& lo, const Vec3& hi);

// Uniform double in [0, 1) from a 64-bit generator, bit-reproducible across
// standard libraries (std::uniform_real_distribution is not).
inline double unit_uniform(std::uint64_t bits) {
  return (bits >> 11) * 0x1.0p-53;
}

}  // namespace ballast
