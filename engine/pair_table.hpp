// Combined contact properties of every pair of entities (ball material with ball
// material, ball material with wall), computed once when a material or wall changes
// instead of at every contact every step. The force loop looks a contact's
// stiffnesses and friction up here: one load instead of two material loads, two
// divisions (series stiffness) and a comparison per contact per step.
#pragma once

#include <vector>

#include "engine/material.hpp"
#include "engine/types.hpp"
#include "engine/walls.hpp"

namespace ballast {

struct PairProperties {
  double kn = 0.0, ks = 0.0;  // N/m, the two entities' springs in series
  double mu = 0.0;            // the smaller friction coefficient
};

class PairTable {
 public:
  void build(const std::vector<Material>& materials, const std::vector<Wall>& walls) {
    materials_ = static_cast<Index>(materials.size());
    walls_ = static_cast<Index>(walls.size());
    ball_ball_.resize(static_cast<std::size_t>(materials_) * materials_);
    ball_wall_.resize(static_cast<std::size_t>(materials_) * walls_);
    for (Index i = 0; i < materials_; ++i) {
      for (Index j = 0; j < materials_; ++j)
        ball_ball_[i * materials_ + j] = combine(materials[i], materials[j]);
      for (Index w = 0; w < walls_; ++w)
        ball_wall_[i * walls_ + w] = combine(materials[i], walls[w].material);
    }
  }
  const PairProperties& balls(Index mi, Index mj) const { return ball_ball_[mi * materials_ + mj]; }
  Index ball_materials() const { return materials_; }
  const PairProperties& wall(Index mi, Index w) const { return ball_wall_[mi * walls_ + w]; }

 private:
  static PairProperties combine(const Material& a, const Material& b) {
    return {series_stiffness(a.kn, b.kn), series_stiffness(a.ks, b.ks),
            contact_friction(a.mu, b.mu)};
  }
  Index materials_ = 0, walls_ = 0;
  std::vector<PairProperties> ball_ball_, ball_wall_;
};

}  // namespace ballast
