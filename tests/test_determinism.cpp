// The same run on 1 and 2 OpenMP threads must end in bit-identical states: every
// parallel loop writes only its own slots and every sum runs in a fixed order.
#include <gtest/gtest.h>
#include <omp.h>

#include "cases/bed.hpp"
#include "engine/state_hash.hpp"
#include "settling_clump_bed.hpp"

using namespace ballast;

namespace {

std::uint64_t run_bed(int threads, bool sphere_fast_path = true, double damping_ratio = 0.1) {
  omp_set_num_threads(threads);
  BedOptions o;
  o.sphere_fast_path = sphere_fast_path;
  o.count = 400;
  o.length = 0.35;
  o.friction = 0.4;
  o.damping_ratio = damping_ratio;
  o.gravity = Vec3(0, 0, -981.0);  // 100 g: a bed forms within a few thousand steps
  Simulation sim = make_bed(o);
  // The cloud has landed and formed a bed (later without dashpots: it bounces more).
  const double until = damping_ratio > 0.0 ? 0.05 : 0.08;
  while (sim.time() < until) sim.step();
  EXPECT_GT(sim.contacts().ball_contacts, 300);  // the bed has really formed
  EXPECT_GT(sim.neighbour_builds(), 10);         // history crossed many rebuilds
  return state_hash(sim);
}

}  // namespace

TEST(Determinism, OneAndTwoThreadsGiveTheSameFinalStateHash) {
  const std::uint64_t one = run_bed(1);
  const std::uint64_t two = run_bed(2);
  EXPECT_EQ(one, two);
  omp_set_num_threads(omp_get_num_procs());
}

// The sphere-only scene's fast path (forces.cpp, integrator.cpp) leaves out reads and
// branches, not arithmetic: it must end in the very state the general path reaches.
TEST(Determinism, SphereFastPathGivesTheGeneralPathsBits) {
  omp_set_num_threads(1);
  const std::uint64_t fast = run_bed(1, true);
  const std::uint64_t general = run_bed(1, false);
  EXPECT_EQ(fast, general);
  omp_set_num_threads(omp_get_num_procs());
}

// Without dashpots a sphere scene's contacts go through the SIMD kernel where the CPU
// has one (sphere_kernel.hpp); each thread takes its share of the flat live list.
TEST(Determinism, SphereKernelGivesTheSameHashOnOneAndTwoThreads) {
  const std::uint64_t one = run_bed(1, true, 0.0);
  const std::uint64_t two = run_bed(2, true, 0.0);
  EXPECT_EQ(one, two);
  omp_set_num_threads(omp_get_num_procs());
}

// Clumps too: many-ball bodies gather forces from many contacts per body, and
// the `full` integrator adds its angular-momentum state.
std::uint64_t run_clump_bed(int threads) {
  omp_set_num_threads(threads);
  BedOptions o;
  o.count = 120;
  o.length = 0.3;
  o.width = 0.15;
  o.clumps = ClumpParams{};  // Table 2 Sample 1's numbers
  o.mass.mode = MassMode::kSum;
  o.rotation = RotationIntegrator::kFull;
  o.friction = 0.4;
  o.damping_ratio = 0.1;
  o.local_damping = 0.2;
  o.gravity = Vec3(0, 0, -981.0);
  Simulation sim = make_bed(o);
  while (sim.time() < 0.04) sim.step();
  EXPECT_GT(sim.contacts().ball_contacts, o.count);  // more than one per clump: a bed
  EXPECT_GT(sim.neighbour_builds(), 10);
  return state_hash(sim);
}

TEST(Determinism, ClumpBedGivesTheSameHashOnOneAndTwoThreads) {
  const std::uint64_t one = run_clump_bed(1);
  const std::uint64_t two = run_clump_bed(2);
  EXPECT_EQ(one, two);
  omp_set_num_threads(omp_get_num_procs());
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
  omp_set_num_threads(1);
  BedOptions o = settling_clump_bed_options();
  o.skip_far_candidates = skip_far_candidates;
  o.adaptive_rebuild = adaptive_rebuild;
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
  omp_set_num_threads(omp_get_num_procs());
}
