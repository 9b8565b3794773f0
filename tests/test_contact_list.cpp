// What a neighbour build leaves in the contact list besides the pairs: each
// candidate's gap at the build, rounded down to a float (the far-candidate skip
// relies on it never exceeding the true gap), the same on any number of threads;
// and the SIMD kernel's flat live sequence, which must be the live lists one after
// the other.
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <limits>
#include <random>

#include "cases/sphere_packing.hpp"
#include "engine/cell_list.hpp"
#include "engine/contact_list.hpp"
#include "test_helpers.hpp"

using namespace ballast;

namespace {

struct Bed {
  std::vector<Vec3> x;
  std::vector<double> r;
  std::vector<Index> body;
  ContactList list;
};

// Spheres of 10–30 mm in a 0.2 m cube, many of them overlapping, plus pairs placed
// at gaps of exactly zero and a few ulps either side of it, where the rounding of
// the gap to a float matters most.
Bed make_bed(std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  Bed bed;
  for (int i = 0; i < 400; ++i) {
    bed.x.emplace_back(0.2 * unit_uniform(rng()), 0.2 * unit_uniform(rng()),
                       0.2 * unit_uniform(rng()));
    bed.r.push_back(0.01 + 0.02 * unit_uniform(rng()));
  }
  for (int k = 0; k < 40; ++k) {
    const Vec3 p(0.3 + 0.01 * k, 0.05, 0.05);
    const double ra = 0.004, rb = 0.0045;
    const double d = std::nextafter(ra + rb, k % 2 ? 1.0 : 0.0) + (k % 3 - 1) * 1e-17 * k;
    bed.x.push_back(p);
    bed.r.push_back(ra);
    bed.x.push_back(p + Vec3(0.0, d, 0.0));
    bed.r.push_back(rb);
  }
  for (Index i = 0; i < Index(bed.x.size()); ++i) bed.body.push_back(i);
  CellList cells;
  cells.build(bed.x, Vec3::Zero(), Vec3(0.8, 0.3, 0.3), 0.07);
  std::vector<Index> a, b;
  find_candidate_pairs(cells, bed.x, bed.r, bed.body, 0.002, a, b);
  bed.list.rebuild(std::move(a), std::move(b), true, Index(bed.x.size()), true);
  return bed;
}

std::vector<float> gaps_on(int threads, Bed& bed) {
  test_support::ScopedThreads team(threads);
  bed.list.touching_first.assign(bed.x.size() + 1, 0);
  bed.list.record_build_gaps(bed.x, bed.r);
  return bed.list.gap_at_build;
}

}  // namespace

TEST(ContactList, BuildGapIsTheLargestFloatNotAboveTheGap) {
  Bed bed = make_bed(7);
  const std::vector<float> g = gaps_on(1, bed);
  ASSERT_GT(g.size(), 500u);
  int touching = 0;
  for (Index c = 0; c < bed.list.size(); ++c) {
    const Index i = bed.list.a[c], j = bed.list.b[c];
    const double gap = (bed.x[i] - bed.x[j]).norm() - (bed.r[i] + bed.r[j]);
    // Not above the gap, and the next float up is: the largest float <= gap.
    EXPECT_LE(double(g[c]), gap) << "candidate " << c;
    EXPECT_GT(double(std::nextafter(g[c], std::numeric_limits<float>::infinity())), gap)
        << "candidate " << c;
    touching += gap < 0.0;
  }
  EXPECT_GT(touching, 100);
  // touching_first counts, per ball, the candidates before it that touched.
  EXPECT_EQ(bed.list.touching_first.back(), touching);
}

TEST(ContactList, BuildGapsAreTheSameOnOneTwoAndThreeThreads) {
  Bed bed = make_bed(11);
  const std::vector<float> one = gaps_on(1, bed);
  for (int threads : {2, 3}) {
    const std::vector<float> many = gaps_on(threads, bed);
    ASSERT_EQ(many.size(), one.size());
    for (std::size_t c = 0; c < one.size(); ++c)
      ASSERT_EQ(std::bit_cast<std::uint32_t>(many[c]), std::bit_cast<std::uint32_t>(one[c]))
          << threads << " threads, candidate " << c;
  }
}

TEST(ContactList, FlatLiveSequenceIsTheLiveListsInOrder) {
  Bed bed = make_bed(13);
  gaps_on(1, bed);
  ContactList& l = bed.list;
  // A cover that keeps some open candidates and leaves others off; a few contacts
  // marked touching whatever their gap.
  l.live_cover = 0.001f;  // half the skin
  for (Index c = 0; c < l.size(); c += 7) l.active[c] = 1;
  l.refresh_live_a(0, Index(bed.x.size()));
  l.make_flat_live();
  std::vector<Index> want_c, want_a;
  for (Index i = 0; i < Index(bed.x.size()); ++i) {
    ASSERT_EQ(l.flat_first[i], Index(want_c.size())) << "ball " << i;
    for (Index c = l.a_first[i]; c < l.a_first[i + 1]; ++c)
      if (l.active[c] || l.gap_at_build[c] <= l.live_cover) {
        want_c.push_back(c);
        want_a.push_back(i);
      }
  }
  EXPECT_EQ(l.flat_first.back(), Index(want_c.size()));
  EXPECT_EQ(l.flat_c, want_c);
  EXPECT_EQ(l.flat_a, want_a);
  EXPECT_GT(want_c.size(), 100u);
  EXPECT_LT(want_c.size(), std::size_t(l.size()));
  EXPECT_TRUE(l.flat_live_current);
  // Remade after the cover shrinks (the lists are then shorter): no stale tail.
  l.live_cover = -1.0f;
  l.refresh_live_a(0, Index(bed.x.size()));
  l.make_flat_live();
  std::size_t marked = 0;
  for (Index c = 0; c < l.size(); ++c) marked += l.active[c];
  EXPECT_EQ(l.flat_c.size(), marked);
}
