// Contacts, stored as a structure of arrays. The list holds every candidate pair
// from the last neighbour build (pairs within reach + skin); a pair is `active`
// while its entities actually overlap. Keeping inactive candidates lets a contact
// open and close between rebuilds without reallocating anything.
//
// One type serves both kinds of contact:
//   ball–ball: a < b are ball indices;     ball–wall: a is the ball, b the wall.
// Sign conventions: `normal` (implied) points from b to a; `force` is the total
// force on a (normal + shear + dashpot), N; b receives −force. `point` is where the
// force acts, so the torque on a's body is (point − x_body) × force.
//
// History: the shear force is the only state carried from step to step. It lives in
// `shear_force` and survives neighbour rebuilds by a merge on the sorted (a, b) keys.
// A frictionless scene never allocates it.
#pragma once

#include <cstdint>
#include <vector>

#include "engine/types.hpp"

namespace ballast {

struct ContactList {
  std::vector<Index> a, b;           // keys, sorted lexicographically
  std::vector<Vec3> shear_force;     // N on a, history; empty when the scene is frictionless
  std::vector<Vec3> force;           // N on a
  std::vector<Vec3> point;           // m
  std::vector<double> normal_force;  // N, elastic part kn·overlap (what PFC reports)
  std::vector<double> slip_work;     // J dissipated by Coulomb slip this step
  std::vector<double> viscous_work;  // J dissipated by the dashpots this step
  std::vector<std::uint8_t> active;  // 1 while overlapping

  // Per ball: the contacts it takes part in, as entries 2·contact + side
  // (side 0: the ball is a and receives +force; side 1: it is b, receives −force).
  std::vector<Index> ball_offset;  // size n_balls + 1
  std::vector<Index> ball_entry;

  Index size() const { return static_cast<Index>(a.size()); }

  // Replaces the candidate set by (new_a, new_b), sorted, and carries the shear force
  // of every pair present in both the old and new sets. Per-ball lookup is rebuilt
  // for `n_balls` balls; `b_is_ball` says whether b also gets entries.
  void rebuild(std::vector<Index>&& new_a, std::vector<Index>&& new_b, bool keep_history,
               Index n_balls, bool b_is_ball);

  // Allocates (zeroed) or frees the shear history when friction is switched on/off.
  void set_history(bool on);
  bool has_history() const { return history_; }

 private:
  bool history_ = false;
};

}  // namespace ballast
