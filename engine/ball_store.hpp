// Balls: the spheres that touch things. Every ball belongs to exactly one rigid
// body (a sphere is a one-ball body). Structure of arrays: the force loop reads
// position/radius/body/material; the offsets are only touched when a clump moves.
#pragma once

#include <vector>

#include "engine/types.hpp"

namespace ballast {

struct BallStore {
  // hot: read by the neighbour search and the contact loop every step
  std::vector<Vec3> position;   // world position of the centre, m
  std::vector<double> radius;   // m
  std::vector<Index> body;      // owning body
  std::vector<Index> material;  // index into Simulation's material table
  // warm: read when clumps move
  std::vector<Vec3> offset;  // centre in the owning body's principal frame, m
  // cold: energy ledger, per ball so that sums never depend on thread count
  std::vector<double> friction_dissipated;  // J, slip at contacts this ball owns
  std::vector<double> viscous_dissipated;   // J, contact dashpots this ball owns

  Index size() const { return static_cast<Index>(radius.size()); }

  Index add(const Vec3& pos, double r, Index owner, Index mat, const Vec3& local_offset) {
    position.push_back(pos);
    radius.push_back(r);
    body.push_back(owner);
    material.push_back(mat);
    offset.push_back(local_offset);
    friction_dissipated.push_back(0.0);
    viscous_dissipated.push_back(0.0);
    return size() - 1;
  }
};

}  // namespace ballast
