// The early neighbour rebuild (engine/rebuild_policy.hpp): the renewal rule on its
// own, and in a settling clump bed, where it must leave the motion as it was and
// shorten the live lists.
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>

#include "cases/bed.hpp"
#include "engine/rebuild_policy.hpp"
#include "engine/state_hash.hpp"
#include "settling_clump_bed.hpp"
#include "test_helpers.hpp"

using namespace ballast;

namespace {

// Steps until the policy asks for a build when the live lists gain `rate` candidates
// a step over the base (refreshed every step); -1 if it never does within `limit`.
long steps_to_build(const RebuildPolicy& started, double rate, long limit) {
  RebuildPolicy p = started;
  const long base = 100;
  p.live_count(base);
  for (long t = 1; t <= limit; ++t) {
    if (p.step_taken()) return t;
    p.live_count(base + std::lround(rate * double(t)));
  }
  return -1;
}

// The renewal optimum for an excess a·(t − 1) at step t: the smallest T with
// a·T(T − 1)/2 ≥ C (then w·T = a·T(T − 1) ≥ C + W, W = a·T(T − 1)/2).
long optimum(double cost, double rate) {
  long t = 1;
  while (rate * double(t) * double(t - 1) / 2.0 < cost) ++t;
  return t;
}

}  // namespace

TEST(RebuildPolicy, BuildCostCountsBallsAndCandidates) {
  RebuildPolicy p;
  p.start(1000, 5000);
  EXPECT_DOUBLE_EQ(p.build_cost(), 1000 * RebuildPolicy::kBuildCostPerBall +
                                       5000 * RebuildPolicy::kBuildCostPerCandidate);
}

// An excess growing linearly is rebuilt at the renewal optimum, and the interval
// scales as 1/√a: four times the rate, half the steps.
TEST(RebuildPolicy, LinearlyGrowingExcessRebuildsAtTheRenewalOptimum) {
  RebuildPolicy p;
  p.start(20, 100);
  const double c = p.build_cost();
  ASSERT_GT(c, 1000.0);
  const long slow = steps_to_build(p, 1.0, 100000), fast = steps_to_build(p, 4.0, 100000);
  EXPECT_EQ(slow, optimum(c, 1.0));
  EXPECT_EQ(fast, optimum(c, 4.0));
  EXPECT_NEAR(double(slow) / double(fast), 2.0, 0.1);
}

// A cloud falling apart has its whole excess from the first steps on: a build would
// be undone at once, and w T < C + w T for ever.
TEST(RebuildPolicy, ExcessAtItsMaximumFromTheStartNeverRebuilds) {
  RebuildPolicy p;
  p.start(100, 1000);
  p.live_count(50);
  p.live_count(900);  // the bound covers most candidates one refresh later
  for (long t = 0; t < 1000000; ++t) ASSERT_FALSE(p.step_taken()) << "step " << t;
}

TEST(RebuildPolicy, NoExcessOrNoCountNeverRebuilds) {
  RebuildPolicy still;
  still.start(100, 1000);
  still.live_count(50);
  RebuildPolicy uncounted;  // the lists were never made since the build
  uncounted.start(100, 1000);
  for (long t = 0; t < 100000; ++t) {
    ASSERT_FALSE(still.step_taken());
    ASSERT_FALSE(uncounted.step_taken());
  }
  EXPECT_EQ(still.steps_since_build(), 100000);
  EXPECT_EQ(uncounted.steps_since_build(), 0);
}

namespace {

struct SettlingRun {
  std::uint64_t bodies_hash = 0;  // positions, velocities, orientations: the motion
  long builds = 0, early_builds = 0;
  double mean_live = 0.0;  // live candidates per step
};

// 120 clumps fall at 100 g onto the rubber base and settle (dashpots, so that they
// come to rest within a few hundredths of a second), with a fixed dt, the automatic
// one of the start, so that a build cannot change the timestep.
SettlingRun settle_clumps(bool adaptive_rebuild) {
  test_support::ScopedThreads one(1);
  BedOptions o = settling_clump_bed_options();
  Simulation probe = make_bed(o);
  probe.prepare();
  o.sim.fixed_dt = probe.dt();
  o.sim.adaptive_rebuild = adaptive_rebuild;
  Simulation sim = make_bed(o);
  double live = 0.0;
  long steps = 0;
  for (; sim.time() < 0.08; ++steps) {
    sim.step();
    live += double(sim.live_candidates());
  }
  EXPECT_GT(sim.contacts().ball_contacts, o.count);  // a bed has formed
  SettlingRun r;
  r.bodies_hash = motion_hash(sim.bodies());
  r.builds = sim.neighbour_builds();
  r.early_builds = sim.early_neighbour_builds();
  r.mean_live = live / double(steps);
  return r;
}

}  // namespace

// A build keeps every touching pair's state and an open pair holds nothing, so early
// builds must leave every bit of the motion as it was, while the force pass
// evaluates fewer candidates.
TEST(RebuildPolicy, EarlyBuildsLeaveTheMotionBitForBitAndShortenTheLiveLists) {
  const SettlingRun adaptive = settle_clumps(true);
  const SettlingRun half_skin = settle_clumps(false);
  EXPECT_EQ(adaptive.bodies_hash, half_skin.bodies_hash);
  EXPECT_EQ(half_skin.early_builds, 0);
  EXPECT_GT(adaptive.early_builds, 5);
  EXPECT_GT(adaptive.builds, half_skin.builds);
  EXPECT_LT(adaptive.mean_live, 0.8 * half_skin.mean_live)
      << "adaptive " << adaptive.mean_live << ", half-skin " << half_skin.mean_live;
  std::printf(
      "mean live candidates a step: %.0f with early builds (%ld builds, %ld early), "
      "%.0f with the half-skin rule alone (%ld builds)\n",
      adaptive.mean_live, adaptive.builds, adaptive.early_builds, half_skin.mean_live,
      half_skin.builds);
}
