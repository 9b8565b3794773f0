#include "engine/contact_list.hpp"

namespace ballast {

void ContactList::rebuild(std::vector<Index>&& new_a, std::vector<Index>&& new_b, bool keep_history,
                          Index n_balls, bool b_is_ball) {
  const std::size_t n = new_a.size();
  std::vector<Vec3> new_shear;
  if (keep_history) {
    // Two-pointer merge on sorted keys: O(old + new), no hashing, deterministic.
    new_shear.assign(n, Vec3::Zero());
    std::size_t o = 0;
    const std::size_t old_n = a.size();
    for (std::size_t k = 0; k < n && o < old_n; ++k) {
      while (o < old_n && (a[o] < new_a[k] || (a[o] == new_a[k] && b[o] < new_b[k]))) ++o;
      if (o < old_n && a[o] == new_a[k] && b[o] == new_b[k] && !shear_force.empty())
        new_shear[k] = shear_force[o];
    }
  }
  a = std::move(new_a);
  b = std::move(new_b);
  shear_force = std::move(new_shear);
  history_ = keep_history;
  force.assign(n, Vec3::Zero());
  point.assign(n, Vec3::Zero());
  normal_force.assign(n, 0.0);
  slip_work.assign(n, 0.0);
  viscous_work.assign(n, 0.0);
  active.assign(n, 0);

  // Per-ball entries by counting sort; entries of a ball come in contact order.
  ball_offset.assign(n_balls + 1, 0);
  for (std::size_t c = 0; c < n; ++c) {
    ++ball_offset[a[c] + 1];
    if (b_is_ball) ++ball_offset[b[c] + 1];
  }
  for (Index i = 0; i < n_balls; ++i) ball_offset[i + 1] += ball_offset[i];
  ball_entry.resize(ball_offset[n_balls]);
  std::vector<Index> fill(ball_offset.begin(), ball_offset.end() - 1);
  for (std::size_t c = 0; c < n; ++c) {
    ball_entry[fill[a[c]]++] = static_cast<Index>(2 * c);
    if (b_is_ball) ball_entry[fill[b[c]]++] = static_cast<Index>(2 * c + 1);
  }
}

void ContactList::set_history(bool on) {
  history_ = on;
  if (on)
    shear_force.assign(a.size(), Vec3::Zero());
  else
    shear_force.clear();
}

}  // namespace ballast
