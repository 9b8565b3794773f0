// The engine's spatial numbering (engine/spatial_order.hpp, Simulation::
// sort_bodies_spatially): bodies come out cell by cell across the bed's smallest
// section, whatever order they came in; a sorted bed steps to the same bits as the
// bed built in that order (every per-body and per-ball field follows its body), on
// one thread or two; a bed already numbered cell by cell keeps its numbering.
#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <random>
#include <stdexcept>

#include "cases/bed.hpp"
#include "cases/bench_bed.hpp"
#include "cases/packing_bodies.hpp"
#include "engine/spatial_order.hpp"
#include "engine/state_hash.hpp"
#include "settling_clump_bed.hpp"
#include "test_helpers.hpp"

using namespace ballast;

namespace {

// The packing with its bodies in the order `from` (entry k: the body that becomes k).
Packing renumbered(const Packing& p, const std::vector<Index>& from) {
  Packing out;
  out.clumps = p.clumps;
  for (Index b : from) {
    const Index first = p.body_first[b], last = p.body_first[b + 1];
    out.add_body(long(out.bodies()), {p.centre.begin() + first, p.centre.begin() + last},
                 {p.radius.begin() + first, p.radius.begin() + last});
  }
  return out;
}

std::vector<Index> shuffled(Index n, std::uint64_t seed) {
  std::vector<Index> from(static_cast<std::size_t>(n));
  std::iota(from.begin(), from.end(), Index(0));
  std::shuffle(from.begin(), from.end(), std::mt19937_64(seed));
  return from;
}

// 120 Sample 1 clumps caught settling at 100 g: overlapping, so the next steps load
// every field of the contacts, balls and bodies.
const Packing& falling_clumps() {
  static const Packing bed = [] {
    Simulation sim = make_bed(settling_clump_bed_options());
    while (sim.time() < 0.035) sim.step();
    // Lifted out of the rubber base it sank into (centimetres at 100 g), onto the
    // bench bed's stiff floor.
    Packing p = packing_of(sim);
    double bottom = 1.0;
    for (Index k = 0; k < p.balls(); ++k) bottom = std::min(bottom, p.centre[k].z() - p.radius[k]);
    for (Vec3& c : p.centre) c.z() -= bottom;
    return p;
  }();
  return bed;
}

BenchBedOptions box_for_falling_clumps(bool keep_file_order) {
  BenchBedOptions o;
  o.length = 0.3;
  o.width = 0.15;
  // The settling bed's law and gravity: its contacts (about 60) carry on.
  o.contact_stiffness = 0.5 * settling_clump_bed_options().stiffness;
  o.gravity = 981.0;
  o.dt = 5e-7;
  o.local_damping = 0.2;
  o.friction = 0.4;
  o.keep_file_order = keep_file_order;
  return o;
}

std::uint64_t hash_after_steps(Simulation& sim, long steps) {
  sim.run(steps);
  return state_hash(sim);
}

}  // namespace

TEST(SpatialOrder, NumbersCellByCellAcrossTheSmallestSection) {
  // A 14 × 6 × 8 lattice of 50 mm cells (0.7 × 0.3 × 0.4 m): the smallest section
  // is across x, so x is the slowest axis, then z, y, x.
  std::vector<Vec3> centre;
  for (int i = 0; i < 14; ++i)
    for (int j = 0; j < 6; ++j)
      for (int k = 0; k < 8; ++k)
        centre.emplace_back(0.025 + 0.05 * i, 0.025 + 0.05 * j, 0.025 + 0.05 * k);
  std::vector<Vec3> mixed;
  for (Index k : shuffled(Index(centre.size()), 7)) mixed.push_back(centre[std::size_t(k)]);
  const SpatialOrder o = spatial_order(mixed, 0.05);
  EXPECT_EQ(o.slowest_axis, 0);
  ASSERT_EQ(o.order.size(), mixed.size());
  for (std::size_t k = 1; k < o.order.size(); ++k) {
    const Vec3& a = mixed[std::size_t(o.order[k - 1])];
    const Vec3& b = mixed[std::size_t(o.order[k])];
    ASSERT_LE(a.x(), b.x() + 1e-12) << "x is not the slowest axis at entry " << k;
    if (a.x() == b.x()) {
      ASSERT_LE(a.z(), b.z() + 1e-12) << "z is not the next axis at entry " << k;
    }
  }
  // Walked cell by cell, y fastest: rows of 6 cells, 5 steps of one cell and one of
  // sqrt(5² + 1) back to the next row's start, a mean of 1.68, a little more at
  // the ends of the x slabs.
  EXPECT_LT(o.step_after, 2.0);
  EXPECT_GT(o.step_before, 5.0) << "a shuffled lattice steps across the box";
  EXPECT_TRUE(o.pays());
}

TEST(SpatialOrder, DoesNotDependOnTheOrderBodiesComeIn) {
  const Packing& bed = falling_clumps();
  std::vector<std::vector<double>> numbered;
  for (std::uint64_t seed : {1u, 2u}) {
    Simulation sim = make_bench_bed(renumbered(bed, shuffled(bed.bodies(), seed)),
                                    box_for_falling_clumps(false));
    std::vector<double> x;
    for (const Vec3& p : sim.balls().position) x.insert(x.end(), {p.x(), p.y(), p.z()});
    numbered.push_back(x);
  }
  EXPECT_EQ(numbered[0], numbered[1]);
}

// The sort must carry every field: a shuffled bed, sorted, steps to the bits of the
// same bed built directly in the sorted order. Two shufflings give those bits too.
TEST(SpatialOrder, SortedBedStepsAsTheBedBuiltInThatOrder) {
  const Packing& bed = falling_clumps();
  const Packing mixed = renumbered(bed, shuffled(bed.bodies(), 3));
  Simulation sorted = make_bench_bed(mixed, box_for_falling_clumps(false));
  // The order the sort chooses (and that it pays on a shuffled bed).
  Simulation again = make_bench_bed(mixed, box_for_falling_clumps(true));
  const SpatialOrder applied = again.sort_bodies_spatially();
  ASSERT_TRUE(applied.applied) << describe(applied);
  EXPECT_EQ(state_hash(again), state_hash(sorted));
  Simulation direct =
      make_bench_bed(renumbered(mixed, applied.order), box_for_falling_clumps(true));
  EXPECT_EQ(state_hash(sorted), state_hash(direct)) << "the sort left a field in the old order";
  const std::uint64_t h = hash_after_steps(sorted, 1500);
  EXPECT_GT(sorted.contacts().ball_contacts, 30) << "the bed must be in contact to test anything";
  EXPECT_EQ(hash_after_steps(direct, 1500), h);
  Simulation other =
      make_bench_bed(renumbered(bed, shuffled(bed.bodies(), 4)), box_for_falling_clumps(false));
  EXPECT_EQ(hash_after_steps(other, 1500), h);
}

TEST(SpatialOrder, SortedBedIsBitIdenticalOnOneAndTwoThreads) {
  const Packing& bed = falling_clumps();
  const Packing mixed = renumbered(bed, shuffled(bed.bodies(), 5));
  std::uint64_t h[2];
  for (int threads : {1, 2}) {
    test_support::ScopedThreads team(threads);
    Simulation sim = make_bench_bed(mixed, box_for_falling_clumps(false));
    h[threads - 1] = hash_after_steps(sim, 2000);
  }
  EXPECT_EQ(h[0], h[1]);
}

// Our generator numbers its beds cell by cell (with other cells): sorting them would
// change their bits for nothing, and does not happen.
TEST(SpatialOrder, GeneratedBedKeepsItsNumbering) {
  for (bool clumps : {false, true}) {
    BedOptions o;
    if (clumps) o.clumps = ClumpParams{};
    Simulation sim = make_bed(o);
    const std::vector<Vec3> before = sim.bodies().position;
    const SpatialOrder order = sim.sort_bodies_spatially();
    EXPECT_FALSE(order.applied) << (clumps ? "clumps: " : "spheres: ") << describe(order);
    EXPECT_EQ(sim.bodies().position, before);
    // The same bed numbered at random is sorted.
    o.spatial_order = false;
    Simulation random = make_bed(o);
    EXPECT_TRUE(random.sort_bodies_spatially().applied) << (clumps ? "clumps" : "spheres");
  }
}

TEST(SpatialOrder, OnlyBeforeTheFirstStep) {
  Simulation sim = make_bench_bed(falling_clumps(), box_for_falling_clumps(true));
  sim.step();
  EXPECT_THROW(sim.sort_bodies_spatially(true), std::logic_error);
}
