// Simulation::sort_bodies_spatially: the bodies and their balls renumbered before
// the first step, through the stores' field lists (store_fields.hpp), so that no
// per-body or per-ball field is left in the old order.
#include <algorithm>
#include <stdexcept>

#include "engine/simulation.hpp"
#include "engine/store_fields.hpp"

namespace ballast {
namespace {

// An Io for the field lists that puts every vector in a new order: entry k of the
// result is entry from[k] of the vector as it was.
struct Renumber {
  static constexpr bool kReading = false;
  const std::vector<Index>& from;

  template <class... T>
  void operator()(std::vector<T>&... fields) const {
    (apply(fields), ...);
  }
  template <class T>
  void apply(std::vector<T>& v) const {
    if (v.size() != from.size())
      throw std::logic_error("sort_bodies_spatially: a store field has " +
                             std::to_string(v.size()) + " entries, expected " +
                             std::to_string(from.size()));
    std::vector<T> out;
    out.reserve(v.size());
    for (Index k : from) out.push_back(v[std::size_t(k)]);
    v.swap(out);
  }
};

}  // namespace

SpatialOrder Simulation::sort_bodies_spatially(bool always) {
  if (prepared_ || steps_ > 0)
    throw std::logic_error("sort_bodies_spatially: only before the first step");
  double diameter = 0.0;
  for (Index k = 0; k < balls_.size(); ++k)
    diameter = std::max(diameter, 2.0 * (balls_.offset[k].norm() + balls_.radius[k]));
  if (bodies_.size() < 2) return SpatialOrder{};
  SpatialOrder order = spatial_order(bodies_.position, diameter);
  if (!always && !order.pays()) return order;

  // Balls follow their bodies, each body's balls in their order.
  std::vector<Index> ball_from;
  ball_from.reserve(std::size_t(balls_.size()));
  for (Index b : order.order)
    for (Index j = 0; j < bodies_.ball_count[b]; ++j)
      ball_from.push_back(bodies_.first_ball[b] + j);
  std::vector<Index> new_index(order.order.size());
  for (std::size_t k = 0; k < order.order.size(); ++k)
    new_index[std::size_t(order.order[k])] = Index(k);

  Renumber bodies{order.order}, balls{ball_from};
  ballast::state_fields(bodies, bodies_);
  ballast::state_fields(balls, balls_);
  // Radius expansion's full-size geometry, per ball, once used.
  if (!full_radius_.empty()) balls.apply(full_radius_);
  if (!full_offset_.empty()) balls.apply(full_offset_);
  for (Index& b : balls_.body) b = new_index[std::size_t(b)];
  for (Index b = 0, first = 0; b < bodies_.size(); first += bodies_.ball_count[b], ++b)
    bodies_.first_ball[b] = first;
  order.applied = true;
  return order;
}

}  // namespace ballast
