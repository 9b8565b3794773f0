// Contacts, stored as a structure of arrays. The list holds every candidate pair
// from the last neighbour build (pairs within reach + skin); a pair is `active`
// while its entities actually overlap. Keeping inactive candidates lets a contact
// open and close between rebuilds without reallocating anything.
//
// One type serves both kinds of contact:
//   ball–ball: a < b are ball indices;     ball–wall: a is the ball, b the wall.
// Sign conventions: `normal` (implied) points from b to a; the contact's total
// force F (normal + shear + dashpot, N) acts on a, and b receives −F.
//
// How forces reach bodies without atomics: the force pass runs body by body and,
// within a body, ball by ball, each ball evaluating the contacts it is side a of
// (the list is sorted by a, so they are the contiguous range a_first[i] ..
// a_first[i+1]) and summing their wrenches on the body in registers; only the wrench
// on side b is stored per contact (b_wrench). A body then adds its a-side sum and
// the b_wrench of the contacts its balls are side b of (b_first/b_contact), always
// in the same order. Ball–wall lists store −F on the wall in b_wrench (their torque
// is unused). A contact that is not touching holds a zero b_wrench; the gather reads
// the list's extra zero slot in its place, selected by a mask rather than a branch
// (it mispredicted often), so that a clump bed's many open candidates cost no memory
// traffic.
//
// Energy: the work a contact dissipates (Coulomb slip, dashpots) is summed on the
// contact while the list lives, and handed to the ball ledger of side a by
// flush_dissipation() before a rebuild. Sliding is rare in a settled bed, so this
// costs a store only when something slips, instead of two stores every step.
//
// History: the shear force is the only state carried from step to step. It lives in
// `shear_force` and survives neighbour rebuilds by a merge on the sorted (a, b) keys.
// A frictionless scene never allocates it.
//
// Far candidates: most candidates of a clump bed never touch between two builds
// (Sample 1: 85,103 candidates, 4,472 touching). Each ball–ball candidate keeps its
// gap at the build, g0 = |x_a − x_b| − (r_a + r_b). If no ball has moved more than D
// since then and no radius has grown more than G, the gap now is at least g0 − 2(D + G),
// so a candidate with g0 above that bound cannot touch and, if it was not touching
// before, the force pass has nothing to do for it (Simulation::far_gap()). Skipping
// it computes nothing the full test would not have found, so the bits are the same.
//
// Live candidates: testing every candidate for the skip each step was itself the
// cost, and in a sphere bed, where half the candidates touch in no pattern, its
// branch mispredicted about once a candidate. So the candidates that may touch are
// listed instead, in contact order: those touching, or whose g0 is at most a cover
// chosen above the bound. While the bound stays at or below the cover, a candidate
// left off the list is one the skip test would have skipped (it was open when the
// list was made and, never evaluated since, is open still). Simulation::step()
// raises the cover, and the force pass and the gather refresh the lists, when the
// bound passes it; the lists hold a subsequence of the same order, so the bits are
// the same again.
#pragma once

#include <cstdint>
#include <limits>
#include <vector>

#include "engine/types.hpp"

namespace ballast {

// What a contact exerts on one of its two sides.
struct Wrench {
  Vec3 force;   // N
  Vec3 torque;  // N·m about that side's body's centre of mass
};

struct ContactList {
  std::vector<Index> a, b;        // keys, sorted lexicographically
  std::vector<Vec3> shear_force;  // N on a, history; empty when the scene is frictionless
  // On side b: −F and its moment about b's centre of mass. One more entry than there
  // are contacts, always zero, which the gather reads for an open contact.
  std::vector<Wrench> b_wrench;
  std::vector<double> normal_force;   // N, elastic part kn·overlap (what PFC reports)
  std::vector<double> slip_total;     // J dissipated by Coulomb slip since the last rebuild
  std::vector<double> viscous_total;  // J dissipated by the dashpots since the last rebuild
  std::vector<std::uint8_t> active;   // 1 while overlapping
  // m, the gap at the last build rounded down to a float (half the bytes to stream);
  // −∞ until record_build_gaps(), which no skip test passes.
  std::vector<float> gap_at_build;

  // Per ball i: its contacts as side a are a_first[i] .. a_first[i + 1] (size n_balls + 1).
  std::vector<Index> a_first;
  // Per ball i: how many of the candidates before a_first[i] touched at the build
  // (record_build_gaps; zeros until then). What the force pass costs is mostly its
  // touching contacts, so its work split counts them (forces.cpp).
  std::vector<Index> touching_first;
  // Per ball i (ball–ball lists only): its contacts as side b are
  // b_contact[b_first[i] .. b_first[i + 1]], in contact order.
  std::vector<Index> b_first, b_contact;

  // Live candidates (ball–ball lists only; see above). The list holds every
  // candidate c with active[c] or gap_at_build[c] <= live_cover (m), marked live[c].
  // Per ball i, its live side-a candidates are live_a[a_first[i] .. live_a_end[i]).
  // Per body whose first ball is k, the live side-b contacts of all its balls are
  // live_b[b_first[k] .. live_b_end[k]). live_cover is −∞ after a rebuild, so the
  // first step makes the lists.
  float live_cover = -std::numeric_limits<float>::infinity();
  std::vector<std::uint8_t> live;
  std::vector<Index> live_a, live_a_end, live_b, live_b_end;

  // The live side-a candidates of all balls as one flat sequence, in contact order
  // (ball–ball lists only; make_flat_live()): flat_c[k] is a contact, flat_a[k] its
  // side a, and ball i's are flat_first[i] .. flat_first[i + 1]. The SIMD sphere
  // kernel takes them a register's width at a time, with no loop per ball.
  std::vector<Index> flat_c, flat_a, flat_first;
  // Whether the flat sequence matches the live lists: cleared by rebuild() and by the
  // caller when it remakes the lists without it, set by make_flat_live().
  bool flat_live_current = false;

  Index size() const { return static_cast<Index>(a.size()); }
  // Total force on a, N (b receives its opposite).
  Vec3 force(Index c) const { return -b_wrench[c].force; }

  // Replaces the candidate set by (new_a, new_b), sorted, and carries the shear force
  // of every pair present in both the old and new sets. Per-ball ranges are rebuilt
  // for `n_balls` balls; `b_is_ball` says whether b is a ball (gets b entries).
  void rebuild(std::vector<Index>&& new_a, std::vector<Index>&& new_b, bool keep_history,
               Index n_balls, bool b_is_ball);

  // Ball–ball lists: fills gap_at_build from the balls' positions (m) and radii (m)
  // at the build, each value rounded down so that it never exceeds the true gap.
  void record_build_gaps(const std::vector<Vec3>& position, const std::vector<double>& radius);

  // Makes the live side-a lists of balls [ball_lo, ball_hi) and marks live[c] of
  // their candidates, for the current live_cover. Threads take disjoint ranges.
  void refresh_live_a(Index ball_lo, Index ball_hi);
  // Makes the live side-b list of the body whose balls are [first, last), from the
  // live marks of refresh_live_a (which must have run for every ball).
  void refresh_live_b(Index first, Index last);
  // Makes the flat sequence from the live side-a lists of every ball (serially,
  // after refresh_live_a has run for all of them).
  void make_flat_live();

  // Adds each contact's dissipated work to the ledgers of its side-a ball (in
  // contact order, so the sums do not depend on threads) and zeroes it.
  void flush_dissipation(std::vector<double>& friction, std::vector<double>& viscous);

  // Allocates (zeroed) or frees the shear history when friction is switched on/off.
  void set_history(bool on);
  bool has_history() const { return history_; }

  // Every field, for checkpoints (engine/state_io.hpp; defined in simulation_state.cpp).
  template <class Io>
  void state_fields(Io& io);

 private:
  bool history_ = false;
};

}  // namespace ballast
