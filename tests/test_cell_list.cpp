// The linked-cell search must find exactly the pairs a brute-force search finds,
// including pairs placed a hair inside and a hair outside the search distance.
#include <gtest/gtest.h>

#include <random>

#include "cases/sphere_packing.hpp"
#include "engine/cell_list.hpp"

using namespace ballast;

namespace {

struct Config {
  std::vector<Vec3> x;
  std::vector<double> r;
  std::vector<Index> body;
};

Config random_config(int n, std::uint64_t seed, double box) {
  std::mt19937_64 rng(seed);
  Config c;
  for (int i = 0; i < n; ++i) {
    c.x.emplace_back(box * unit_uniform(rng()), box * unit_uniform(rng()),
                     box * unit_uniform(rng()));
    c.r.push_back(0.01 + 0.02 * unit_uniform(rng()));
    c.body.push_back(i / 3);  // triples share a body: never paired with each other
  }
  return c;
}

// Appends pairs at distance reach·(1 ± 1e-9): the boundary cases.
void add_near_touching(Config& c, double skin, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  for (int k = 0; k < 50; ++k) {
    const Vec3 p(0.1 + 0.3 * unit_uniform(rng()), 0.1 + 0.3 * unit_uniform(rng()),
                 0.1 + 0.3 * unit_uniform(rng()));
    const double ra = 0.015, rb = 0.02;
    const double reach = ra + rb + skin;
    const double d = reach * (k % 2 ? 1.0 + 1e-9 : 1.0 - 1e-9);
    const Vec3 dir = Vec3(unit_uniform(rng()) - 0.5, unit_uniform(rng()) - 0.5, 0.3).normalized();
    const Index body = c.body.empty() ? 0 : c.body.back() + 1;
    c.x.push_back(p);
    c.r.push_back(ra);
    c.body.push_back(body);
    c.x.push_back(p + d * dir);
    c.r.push_back(rb);
    c.body.push_back(body + 1);
  }
}

}  // namespace

TEST(CellList, FindsExactlyTheBruteForcePairs) {
  for (std::uint64_t seed : {1u, 2u, 3u, 4u}) {
    const double skin = 0.004;
    Config c = random_config(1500, seed, 0.5);
    add_near_touching(c, skin, seed + 100);
    CellList cells;
    cells.build(c.x, Vec3::Zero(), Vec3::Constant(0.5), 2 * 0.03 + skin);
    std::vector<Index> a, b, ea, eb;
    find_candidate_pairs(cells, c.x, c.r, c.body, skin, a, b);
    brute_force_pairs(c.x, c.r, c.body, skin, ea, eb);
    ASSERT_GT(ea.size(), 1000u);
    EXPECT_EQ(a, ea) << "seed " << seed;
    EXPECT_EQ(b, eb) << "seed " << seed;
  }
}

TEST(CellList, BallsOutsideTheGridAreStillFound) {
  Config c;
  c.x = {Vec3(-0.05, 0.1, 0.1), Vec3(-0.02, 0.1, 0.1), Vec3(0.6, 0.6, 0.6)};
  c.r = {0.02, 0.02, 0.02};
  c.body = {0, 1, 2};
  CellList cells;
  cells.build(c.x, Vec3::Zero(), Vec3::Constant(0.5), 0.05);
  std::vector<Index> a, b;
  find_candidate_pairs(cells, c.x, c.r, c.body, 0.001, a, b);
  ASSERT_EQ(a.size(), 1u);
  EXPECT_EQ(a[0], 0);
  EXPECT_EQ(b[0], 1);
}

// Tiny balls in a large domain: the grid is capped at kMaxCellsPerBall cells a ball
// (uncapped, this asked for 1024³ cells, 4 GB of counters), and the larger cells
// still find exactly the brute-force pairs.
TEST(CellList, TinyBallsInALargeDomainGetABoundedGrid) {
  const double skin = 1e-5;
  Config c = random_config(300, 7, 0.5);
  for (double& r : c.r) r *= 0.01;  // 0.1-0.3 mm balls, a 0.61 mm cell asked for
  for (Vec3& x : c.x) x *= 0.01;    // crowded into 5 mm, so that some touch
  CellList cells;
  cells.build(c.x, Vec3::Zero(), Vec3::Constant(10.0), 2 * 0.0003 + skin);
  const auto d = cells.dims();
  EXPECT_LE(double(d[0]) * d[1] * d[2], CellList::kMaxCellsPerBall * 300);
  std::vector<Index> a, b, ea, eb;
  find_candidate_pairs(cells, c.x, c.r, c.body, skin, a, b);
  brute_force_pairs(c.x, c.r, c.body, skin, ea, eb);
  ASSERT_GT(ea.size(), 10u);
  EXPECT_EQ(a, ea);
  EXPECT_EQ(b, eb);
}
