// Combined contact properties of every pair of entities (ball material with ball
// material, ball material with wall), computed once when a material or wall changes
// instead of at every contact every step. The force loop looks a contact's pair
// constants (PairProperties, contact_law.hpp, mixed by the scene's law) up here: one
// load instead of two material loads, the law's mixing (two divisions for the linear
// law's series stiffness) and a comparison per contact per step.
#pragma once

#include <vector>

#include "engine/contact_laws.hpp"
#include "engine/material.hpp"
#include "engine/types.hpp"
#include "engine/walls.hpp"

namespace ballast {

class PairTable {
 public:
  // `law`: the scene's contact law, a number of ContactLaws (contact_laws.hpp).
  void build(const std::vector<Material>& materials, const std::vector<Wall>& walls, int law) {
    with_contact_law(law, [&](auto l) { build_for<decltype(l)>(materials, walls); });
  }
  const PairProperties& balls(Index mi, Index mj) const { return ball_ball_[mi * materials_ + mj]; }
  Index ball_materials() const { return materials_; }
  const PairProperties& wall(Index mi, Index w) const { return ball_wall_[mi * walls_ + w]; }

 private:
  template <class Law>
  void build_for(const std::vector<Material>& materials, const std::vector<Wall>& walls) {
    materials_ = static_cast<Index>(materials.size());
    walls_ = static_cast<Index>(walls.size());
    ball_ball_.resize(static_cast<std::size_t>(materials_) * materials_);
    ball_wall_.resize(static_cast<std::size_t>(materials_) * walls_);
    for (Index i = 0; i < materials_; ++i) {
      for (Index j = 0; j < materials_; ++j)
        ball_ball_[i * materials_ + j] = Law::mix(materials[i], materials[j]);
      for (Index w = 0; w < walls_; ++w)
        ball_wall_[i * walls_ + w] = Law::mix(materials[i], walls[w].material);
    }
  }
  Index materials_ = 0, walls_ = 0;
  std::vector<PairProperties> ball_ball_, ball_wall_;
};

}  // namespace ballast
