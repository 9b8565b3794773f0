// The force loop: evaluate every candidate contact, then gather the results into
// body forces and torques. Two passes instead of one scatter so that no two threads
// ever add into the same number: a contact writes only its own slots, a body reads
// only its own balls' contacts, in a fixed order. That is what makes 1 and 2
// threads bit-identical without atomics.
//
// The loops are worksharing loops of their own making: each thread of the enclosing
// parallel region takes its share of equal cost (work_split.hpp). Simulation::step
// calls them inside one parallel region, so a step pays one fork/join instead of one
// per loop. Called outside a parallel region they simply run serially.
#pragma once

#include <cstdint>
#include <vector>

#include "engine/ball_store.hpp"
#include "engine/body_store.hpp"
#include "engine/contact_list.hpp"
#include "engine/pair_table.hpp"
#include "engine/timed_split.hpp"
#include "engine/v3.hpp"
#include "engine/walls.hpp"

namespace ballast {

struct PlaneTable;  // sphere_planes.hpp

struct ForceSettings {
  double dt = 0.0;             // s
  int law = 0;                 // the contact law, a number of ContactLaws (contact_laws.hpp)
  double damping_ratio = 0.0;  // viscous contact damping ratio β (0: none)
  bool friction = true;        // false: frictionless scene, no shear history
  bool all_spheres = false;    // every body is one ball and ball k is body k
  bool ledger = true;          // book slip and dashpot work (SimulationSettings::energy_ledger)
  // > 0: the ball–ball contacts go through the SIMD sphere kernel of that many lanes
  // (sphere_kernel.hpp): a scene of spheres only (all_spheres), of the linear law
  // (the kernel's; any other law ignores this), without dashpots,
  // whose flat live list (ContactList::make_flat_live) is current. Simulation::step
  // decides and keeps the list current; the kernel gives the scalar pass's bits.
  int sphere_kernel_lanes = 0;
  // With the kernel: the walls as it reads them (sphere_planes.hpp), made by the
  // caller for this step; null: the scalar pass takes every wall contact.
  const PlaneTable* planes = nullptr;
  // The pass evaluates the ball–ball list's live candidates only, so the caller
  // keeps its live_cover at or above the bound on how far a gap can have closed
  // (contact_list.hpp, "Far candidates", "Live candidates"; Simulation::far_gap()).
  // true: the caller has just raised live_cover, and the pass remakes the live
  // side-a lists before using them.
  bool refresh_live = false;
  // Thread shares that follow measured time (timed_split.hpp); null: the cost model's
  // equal shares. The caller times each thread's pass, records and updates it.
  TimedSplit* split = nullptr;
};

// The force pass: every candidate contact is evaluated once, by the ball that is its
// side a (contact_list.hpp explains the layout). a_side[b] (one per body) receives
// the sum of the wrenches on body b from the contacts its balls are side a of, ball
// by ball, each ball's ball–ball then ball–wall contacts in contact order; each
// contact stores the wrench on its side b. Each thread takes a share of the bodies
// (work_split.hpp) and there is no barrier at the end: inside a
// parallel region the caller must put `#pragma omp barrier` before anything reads
// the results.
void compute_contacts(const BallStore& balls, const BodyStore& bodies, const PairTable& pairs,
                      const std::vector<Wall>& walls, const ForceSettings& s,
                      ContactList& ball_contacts, ContactList& wall_contacts,
                      std::vector<Wrench>& a_side);

// Sums one body's contact wrenches and gravity into its force and torque: its a-side
// sum, then the b-side wrenches of the live contacts its balls are side b of (an
// open one adds the zero slot, without a branch; a contact off the live list is
// open). A body's balls are contiguous and so are their b entries. Fixed order, any
// thread count. Inline: it runs once per body per step inside the integrator's loop.
// refresh_live: first remake the body's live side-b list (the force pass of this
// step has remade the live marks). kSpheres: a sphere-only scene, where body b is
// ball b, so the body's ball range is not read.
template <bool kSpheres = false>
inline void gather_body_force(Index body, ContactList& bc, const std::vector<Wrench>& a_side,
                              const Vec3& gravity, BodyStore& bodies, bool refresh_live) {
  V3 f = bodies.mass[body] * load(gravity);
  V3 m{0.0, 0.0, 0.0};
  const Index first = kSpheres ? body : bodies.first_ball[body];
  const Index last = kSpheres ? body + 1 : first + bodies.ball_count[body];
  f += load(a_side[body].force);
  m += load(a_side[body].torque);
  // An open contact's wrench is zero, so it may be read from the list's zero slot:
  // the address is selected, not branched on (half of a sphere bed's candidates are
  // open, in no pattern a predictor learns), and a clump bed, whose candidates are
  // 95 % open, no longer streams every candidate's 48 bytes (4 MB a step in Sample 1)
  // through the cache. Adding that zero gives the same bits as adding the stored one.
  if (refresh_live) bc.refresh_live_b(first, last);
  const Wrench* const wrench = bc.b_wrench.data();
  const std::uint8_t* const active = bc.active.data();
  const Index* const live_b = bc.live_b.data();
  const Index none = bc.size();  // ContactList::b_wrench's zero slot
  for (Index e = bc.b_first[first]; e < bc.live_b_end[first]; ++e) {
    const Index c = live_b[e];
    // A sphere scene's live contacts are mostly touching (the bench bed: 3,524 of
    // about 4,300), so there the zero slot saves little traffic and its `active`
    // load lengthened each entry's chain of dependent loads: it reads the contact's
    // own slot, which holds the same zero when the contact is open.
    Index slot = c;
    if constexpr (!kSpheres) {
      const Index open = Index(active[c]) - 1;  // 0 if touching, all bits set if open
      slot = (c & ~open) | (none & open);       // a mask: GCC branched on ?:
    }
    const Wrench& w = wrench[slot];
    f += load(w.force);
    m += load(w.torque);
  }
  store(bodies.force[body], f);
  store(bodies.torque[body], m);
}

// Velocity of a body's material point at world position p (half-step velocities).
inline Vec3 point_velocity(const BodyStore& bodies, Index body, const Vec3& p) {
  return bodies.velocity[body] + bodies.angular_velocity[body].cross(p - bodies.position[body]);
}

}  // namespace ballast
