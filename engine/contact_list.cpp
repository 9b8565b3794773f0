#include "engine/contact_list.hpp"

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

namespace ballast {

void ContactList::rebuild(std::vector<Index>&& new_a, std::vector<Index>&& new_b, bool keep_history,
                          Index n_balls, bool b_is_ball) {
  const std::size_t n = new_a.size();
  // A pair in both the old and the new set keeps what it is: touching or not, its
  // shear force, normal force and side-b wrench. Carrying the shear force alone,
  // with the pair marked open, let a pair that had stopped touching keep a stale
  // shear force (the force pass clears an open contact only once), which it used
  // if it touched again; PFC drops a contact's shear force when it breaks.
  std::vector<Vec3> new_shear(keep_history ? n : 0, Vec3::Zero());
  std::vector<Wrench> new_wrench(n + 1, Wrench{Vec3::Zero(), Vec3::Zero()});  // + the zero slot
  std::vector<double> new_normal(n, 0.0);
  std::vector<std::uint8_t> new_active(n, 0);
  // Two-pointer merge on sorted keys: O(old + new), no hashing, deterministic.
  std::size_t o = 0;
  const std::size_t old_n = a.size();
  for (std::size_t k = 0; k < n && o < old_n; ++k) {
    while (o < old_n && (a[o] < new_a[k] || (a[o] == new_a[k] && b[o] < new_b[k]))) ++o;
    if (o == old_n || a[o] != new_a[k] || b[o] != new_b[k] || !active[o]) continue;
    new_active[k] = 1;
    new_normal[k] = normal_force[o];
    new_wrench[k] = b_wrench[o];
    if (keep_history && !shear_force.empty()) new_shear[k] = shear_force[o];
  }
  a = std::move(new_a);
  b = std::move(new_b);
  shear_force = std::move(new_shear);
  history_ = keep_history;
  b_wrench = std::move(new_wrench);
  normal_force = std::move(new_normal);
  active = std::move(new_active);
  slip_total.assign(n, 0.0);
  viscous_total.assign(n, 0.0);
  gap_at_build.assign(n, -std::numeric_limits<float>::infinity());

  // Side a: the list is sorted by a, so each ball's contacts are one range.
  a_first.assign(n_balls + 1, 0);
  touching_first.assign(n_balls + 1, 0);
  for (std::size_t c = 0; c < n; ++c) ++a_first[a[c] + 1];
  for (Index i = 0; i < n_balls; ++i) a_first[i + 1] += a_first[i];
  // Side b, by counting sort: each ball's entries come in contact order.
  b_first.assign(b_is_ball ? n_balls + 1 : 0, 0);
  b_contact.clear();
  if (!b_is_ball) return;
  for (std::size_t c = 0; c < n; ++c) ++b_first[b[c] + 1];
  for (Index i = 0; i < n_balls; ++i) b_first[i + 1] += b_first[i];
  b_contact.resize(n);
  std::vector<Index> fill(b_first.begin(), b_first.end() - 1);
  for (std::size_t c = 0; c < n; ++c) b_contact[fill[b[c]]++] = static_cast<Index>(c);
  live_cover = -std::numeric_limits<float>::infinity();
  flat_live_current = false;
  live.assign(n, 0);
  live_a.assign(n, 0);
  live_b.assign(n, 0);
  live_a_end.assign(a_first.begin(), a_first.end() - 1);  // empty lists until the refresh
  live_b_end.assign(b_first.begin(), b_first.end() - 1);
}

// Both loops are branch-free: every candidate is written to the next slot and the
// slot advances by its 0/1 mark, since whether a candidate is live follows no
// pattern a predictor could learn.
void ContactList::refresh_live_a(Index ball_lo, Index ball_hi) {
  const float cover = live_cover;
  const std::uint8_t* const on = active.data();
  const float* const gap = gap_at_build.data();
  std::uint8_t* const mark = live.data();
  Index* const out = live_a.data();
  for (Index i = ball_lo; i < ball_hi; ++i) {
    Index w = a_first[i];
    for (Index c = a_first[i]; c < a_first[i + 1]; ++c) {
      const std::uint8_t keep = on[c] | std::uint8_t(gap[c] <= cover);
      mark[c] = keep;
      out[w] = c;
      w += keep;
    }
    live_a_end[i] = w;
  }
}

void ContactList::refresh_live_b(Index first, Index last) {
  const std::uint8_t* const mark = live.data();
  const Index* const entry = b_contact.data();
  Index* const out = live_b.data();
  Index w = b_first[first];
  for (Index e = b_first[first]; e < b_first[last]; ++e) {
    const Index c = entry[e];
    out[w] = c;
    w += mark[c];
  }
  live_b_end[first] = w;
}

void ContactList::make_flat_live() {
  // Sized first and written through pointers: push_back's capacity test per entry,
  // twice per live candidate, cost as much as the copying.
  const Index n_balls = static_cast<Index>(live_a_end.size());
  flat_first.resize(n_balls + 1);
  Index total = 0;
  for (Index i = 0; i < n_balls; ++i) {
    flat_first[i] = total;
    total += live_a_end[i] - a_first[i];
  }
  flat_first[n_balls] = total;
  flat_c.resize(total);
  flat_a.resize(total);
  Index* const fc = flat_c.data();
  Index* const fa = flat_a.data();
  const Index* const la = live_a.data();
  for (Index i = 0; i < n_balls; ++i) {
    Index k = flat_first[i];
    for (Index e = a_first[i]; e < live_a_end[i]; ++e, ++k) {
      fc[k] = la[e];
      fa[k] = i;
    }
  }
  flat_live_current = true;
}

namespace {
// The float next below g (finite), as std::nextafter(g, −∞) gives it, without the
// library call that was a third of this loop's time.
float next_float_down(float g) {
  if (g == 0.0f) return -std::numeric_limits<float>::denorm_min();
  const auto bits = std::bit_cast<std::uint32_t>(g);
  return std::bit_cast<float>(g > 0.0f ? bits - 1u : bits + 1u);
}
}  // namespace

void ContactList::record_build_gaps(const std::vector<Vec3>& position,
                                    const std::vector<double>& radius) {
  // Each candidate's own value, so the threads' ranges change no bit; it is part of
  // the serial time of a build the other threads would wait through.
  const std::int64_t n = static_cast<std::int64_t>(a.size());
#pragma omp parallel for schedule(static)
  for (std::int64_t c = 0; c < n; ++c) {
    const double gap = (position[a[c]] - position[b[c]]).norm() - (radius[a[c]] + radius[b[c]]);
    float g = static_cast<float>(gap);
    if (static_cast<double>(g) > gap) g = next_float_down(g);
    gap_at_build[c] = g;
  }
  // Per-ball counts of the candidates touching at the build, as a prefix.
  for (std::int64_t c = 0; c < n; ++c)
    if (gap_at_build[c] < 0.0f) ++touching_first[a[c] + 1];
  for (std::size_t i = 0; i + 1 < touching_first.size(); ++i)
    touching_first[i + 1] += touching_first[i];
}

void ContactList::flush_dissipation(std::vector<double>& friction, std::vector<double>& viscous) {
  for (std::size_t c = 0; c < a.size(); ++c) {
    friction[a[c]] += slip_total[c];
    viscous[a[c]] += viscous_total[c];
    slip_total[c] = viscous_total[c] = 0.0;
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
