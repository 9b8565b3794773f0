// The same run must end in bit-identical states on any number of OpenMP threads and
// with any thread shares: every parallel loop writes only its own slots, every sum
// runs in a fixed order, and which thread computes an item never changes what it
// computes. The shares follow the wall clock (engine/timed_split.hpp), so besides
// the measured ones each bed runs with shares forced through the test hook
// (Simulation::force_thread_shares): fixed and uneven, and redrawn at every step,
// empty shares included. state_hash covers everything dynamic a run reports
// (positions, velocities, orientations, spins, accumulated rotations, contact
// histories, the energy budget, walls), so "the same hash" means "the same run".
//
// Mutations that must break these tests (tests/mutations.tsv; tests/check_mutations.py
// applies each, rebuilds, runs and restores), and the teams that caught each:
//  - forces.cpp: threads other than 0 sum a ball's side-a contacts in reverse:
//    SphereBed, every team of two or more threads.
//  - the same on threads 2 and up only: SphereBed, the 3- and 4-thread teams.
//  - integrator.cpp: the SIMD leapfrog's dt one ulp longer on threads other than 0:
//    SphereKernel, every team of two or more.
//  - integrator.cpp: the accumulated rotation rounded otherwise on threads other
//    than 0: ClumpBed, every team of two or more. Nothing reads the rotation back,
//    so the hash's rotation field alone sees it: with that field dropped from
//    state_hash as well, the test passed.
//  - integrator.cpp: local damping's booked work rounded otherwise on threads other
//    than 0: ClumpBed, every team of two or more; only the energy ledger sees it
//    (with the ledger and the totals dropped from the hash as well, the test passed).
//  - simulation_step.cpp: the forced shares left off the integrator: ClumpBed, the
//    rule's call count on every forced team.
#include <gtest/gtest.h>

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "cases/bed.hpp"
#include "engine/contact_laws.hpp"
#include "engine/state_hash.hpp"
#include "settling_clump_bed.hpp"
#include "test_helpers.hpp"

using namespace ballast;

namespace {

// One team: its thread count and how the force pass and the integrator share the
// bodies between its threads (an empty rule: by measured time, as in production).
struct Team {
  std::string name;
  int threads;
  TimedSplit::ShareRule rule;
};

// Thread t's weight is weights[t] at every step.
TimedSplit::ShareRule fixed_shares(std::vector<double> weights) {
  return [weights](long, int) { return weights; };
}

std::uint64_t mix(std::uint64_t x) {  // splitmix64's finaliser: well-spread bits
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

// Weights redrawn at every step from (step, thread): a quarter of the shares are
// empty, the rest as uneven as u³ for u uniform, so the boundaries move across the
// bed all the time and a thread sometimes has the whole loop.
TimedSplit::ShareRule redrawn_shares() {
  return [](long update, int threads) {
    std::vector<double> w(threads);
    double total = 0.0;
    for (int t = 0; t < threads; ++t) {
      const double u = double(mix(std::uint64_t(update) * 16 + std::uint64_t(t)) >> 11) * 0x1p-53;
      w[t] = u < 0.25 ? 0.0 : u * u * u;
      total += w[t];
    }
    if (total == 0.0) w[update % threads] = 1.0;
    return w;
  };
}

// The first is the reference; every other must reach its hash.
const std::vector<Team>& teams() {
  static const std::vector<Team> all{
      {"1 thread", 1, {}},
      {"2 threads, measured shares", 2, {}},
      {"2 threads, 70 % to thread 0", 2, fixed_shares({0.7, 0.3})},
      {"3 threads, shares redrawn every step", 3, redrawn_shares()},
      {"4 threads, shares redrawn every step", 4, redrawn_shares()},
  };
  return all;
}

// Runs `o`'s bed until `until` s on `team` and returns the final state's hash; the
// bed must have formed (more than `min_contacts` touching ball pairs).
std::uint64_t run_on(const Team& team, const BedOptions& o, double until, long min_contacts) {
  test_support::ScopedThreads threads(team.threads);
  Simulation sim = make_bed(o);
  // The rule counts its calls: both passes' splits must have asked it at every step.
  const auto calls = std::make_shared<long>(0);
  if (team.rule)
    sim.force_thread_shares([calls, rule = team.rule](long update, int threads) {
      ++*calls;
      return rule(update, threads);
    });
  while (sim.time() < until) sim.step();
  EXPECT_GT(sim.contacts().ball_contacts, min_contacts);
  EXPECT_GT(sim.neighbour_builds(), 10);  // history crossed many rebuilds
  if (team.rule) {
    EXPECT_EQ(*calls, 2 * (sim.step_count() + 1));  // +1: each split's first shares
  }
  return state_hash(sim);
}

void expect_one_hash_on_every_team(const BedOptions& o, double until, long min_contacts) {
  const std::uint64_t reference = run_on(teams()[0], o, until, min_contacts);
  for (std::size_t k = 1; k < teams().size(); ++k) {
    SCOPED_TRACE(teams()[k].name);
    EXPECT_EQ(run_on(teams()[k], o, until, min_contacts), reference);
  }
}

// Three and four threads on a two-core host pay for every step's barriers far more
// than for its work, so the beds below form in few steps: a dense cloud, 200 g, and
// balls an eighth as stiff as the box test's (a timestep 2.8 times as long). A bed
// still forms, with a hundred or more neighbour builds on the way.
constexpr double kSoftening = 1.0 / 8.0;
const Vec3 kGravity(0, 0, -2000.0);

// 400 spheres landing in a narrow box: more than 300 contacts within 0.025 s, about
// 9,000 steps.
BedOptions sphere_bed(double damping_ratio) {
  BedOptions o;
  o.count = 400;
  o.length = 0.35;
  o.volume_fraction = 0.35;
  o.friction = 0.4;
  o.stiffness *= kSoftening;
  o.sim.damping_ratio = damping_ratio;
  o.sim.gravity = kGravity;
  return o;
}

}  // namespace

// With dashpots a sphere scene takes the scalar force pass.
TEST(Determinism, SphereBedGivesOneHashWithAnySharesOnOneToFourThreads) {
  expect_one_hash_on_every_team(sphere_bed(0.1), 0.025, 300);
}

// Without dashpots a sphere scene's contacts go through the SIMD kernel where the CPU
// has one (sphere_kernel.hpp); each thread takes its share of the flat live list.
// The bed bounces more: a longer run to form it.
TEST(Determinism, SphereKernelGivesOneHashWithAnySharesOnOneToFourThreads) {
  expect_one_hash_on_every_team(sphere_bed(0.0), 0.03, 300);
}

// Clumps too: many-ball bodies gather forces from many contacts per body, and
// the `full` integrator adds its angular-momentum state and turns orientations.
TEST(Determinism, ClumpBedGivesOneHashWithAnySharesOnOneToFourThreads) {
  BedOptions o = settling_clump_bed_options();
  o.mass.mode = MassMode::kSum;
  o.sim.rotation = RotationIntegrator::kFull;
  o.stiffness *= kSoftening;
  o.sim.gravity = kGravity;
  expect_one_hash_on_every_team(o, 0.025, o.count);  // more than one contact per clump
}

// Every other contact law of the registry (engine/contact_laws.hpp): a sphere bed
// without dashpots, which the linear law sends through the SIMD kernel and the
// others through the scalar pass, and a clump bed with them.
TEST(Determinism, EveryContactLawGivesOneHashWithAnySharesOnOneToFourThreads) {
  for (int law = 1; law < kContactLawCount; ++law) {
    SCOPED_TRACE(std::string(contact_law_name(law)));
    BedOptions spheres = sphere_bed(0.0);
    spheres.sim.contact_law = std::string(contact_law_name(law));
    expect_one_hash_on_every_team(spheres, 0.03, 300);
    BedOptions clumps = settling_clump_bed_options();
    clumps.sim.contact_law = spheres.sim.contact_law;
    clumps.sim.gravity = kGravity;
    expect_one_hash_on_every_team(clumps, 0.025, clumps.count);
  }
}

// The sphere-only scene's fast path (forces.cpp, integrator.cpp) leaves out reads and
// branches, not arithmetic: it must end in the very state the general path reaches.
TEST(Determinism, SphereFastPathGivesTheGeneralPathsBits) {
  BedOptions general = sphere_bed(0.1);
  general.sim.sphere_fast_path = false;
  EXPECT_EQ(run_on(teams()[0], sphere_bed(0.1), 0.025, 300),
            run_on(teams()[0], general, 0.025, 300));
}

// Far candidates (contact_list.hpp) are skipped only when they provably cannot touch,
// so skipping must not change a bit. The bound has two parts, the balls' shift since
// the build and the growth of their radii; the run exercises both: a settling clump
// bed with many rebuilds, then clumps shrunk by 2 % and grown back step by step, as
// the box test's growth stages do.
std::uint64_t run_growing_clump_bed(bool skip_far_candidates) {
  // Early builds (rebuild_policy.hpp) come only with the skip, and with the automatic
  // timestep each re-estimates dt: off, so that the two runs differ by the skip alone.
  const bool adaptive_rebuild = false;
  test_support::ScopedThreads one(1);
  BedOptions o = settling_clump_bed_options();
  o.sim.skip_far_candidates = skip_far_candidates;
  o.sim.adaptive_rebuild = adaptive_rebuild;
  Simulation sim = make_bed(o);
  while (sim.time() < 0.04) sim.step();
  const long builds_before_growth = sim.neighbour_builds();
  EXPECT_GT(sim.contacts().ball_contacts, o.count);  // a bed, before the growth
  sim.set_size_scale(0.98);
  sim.run(300);
  const int growth_steps = 3000;
  for (int k = 1; k <= growth_steps; ++k) {
    sim.set_size_scale(0.98 + 0.02 * k / growth_steps);
    sim.step();
  }
  sim.run(300);
  EXPECT_GT(builds_before_growth, 10);
  EXPECT_GT(sim.neighbour_builds(), builds_before_growth);  // growth forced rebuilds too
  return state_hash(sim);
}

TEST(Determinism, SkippingFarCandidatesChangesNoBits) {
  const std::uint64_t skipping = run_growing_clump_bed(true);
  const std::uint64_t testing_all = run_growing_clump_bed(false);
  EXPECT_EQ(skipping, testing_all);
}
