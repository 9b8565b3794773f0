// The clump generator (Lu & McDowell 2007 section 2) against the construction rules
// of the paper, the decisions of docs/CLUMPS.md, and the paper's ball counts.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>
#include <stdexcept>
#include <string>

#include "cases/clump_presets.hpp"
#include "engine/clump_generator.hpp"
#include "test_helpers.hpp"

namespace ballast {
namespace {

using test_support::expect_error;

// Rounding of sums of a few terms of size R: 1e-12 relative is ~5000 ulps.
constexpr double kRoundoff = 1e-12;

ClumpParams table2_sample2() {
  ClumpParams q;
  q.directions = 14;
  q.p = 0.5;
  q.balls_per_direction = 2;
  q.c = 0.5;
  q.d3 = 0.2;
  q.edge_balls = 2;
  q.virtual_sphere_factor = 1.31;
  return q;
}

// Everything at once and far from the presets: 14 directions, all used, 4 balls with
// a large c (so the radius floor is reached), 3 edge balls.
ClumpParams extreme() {
  ClumpParams q = table2_sample2();
  q.p = 1.0;
  q.balls_per_direction = 4;
  q.c = 0.9;
  q.d3 = 0.7;
  q.edge_balls = 3;
  return q;
}

std::vector<ClumpParams> all_presets_and_extreme() {
  std::vector<ClumpParams> out;
  for (const std::string& name : available_clump_presets()) {
    out.push_back(load_clump_preset(name).params);
  }
  out.push_back(extreme());
  return out;
}

// Index of ball (direction, k) in g; k = 0 is the central ball.
std::map<std::pair<int, int>, int> direction_index(const ClumpGeometry& g) {
  std::map<std::pair<int, int>, int> at;
  for (int i = 0; i < static_cast<int>(g.radii.size()); ++i) {
    if (g.origins[i].kind == BallKind::kDirection) {
      at[{g.origins[i].direction, g.origins[i].index}] = i;
    }
  }
  return at;
}

TEST(ClumpGenerator, PresetsAreAllThere) {
  const std::vector<std::string> names = available_clump_presets();
  const std::vector<std::string> expected = {"table1/sample1", "table1/sample2", "table1/sample3",
                                             "table1/sample4", "table1/sample5", "table2/sample1",
                                             "table2/sample2"};
  EXPECT_EQ(names, expected);
}

TEST(ClumpGenerator, EveryBallLiesInsideTheVirtualSphere) {
  for (const ClumpParams& q : all_presets_and_extreme()) {
    const double rv = virtual_sphere_radius(q);
    double reach = 0.0;
    for (int i = 0; i < 500; ++i) {
      std::mt19937_64 rng = clump_rng(11, i);
      const ClumpGeometry g = generate_clump(q, rng);
      for (std::size_t b = 0; b < g.radii.size(); ++b) {
        const double far = g.centres[b].norm() + g.radii[b];
        ASSERT_LE(far, rv * (1.0 + kRoundoff)) << "ball " << b << " of clump " << i;
        reach = std::max(reach, far);
      }
    }
    // R = Rv/(1 + n·D3/R) is the largest central ball that fits: a used direction's
    // last ball touches the virtual sphere.
    EXPECT_NEAR(reach, rv, rv * kRoundoff);
  }
}

TEST(ClumpGenerator, FarSurfaceAdvancesByD3PerBall) {
  // x_k + R_k = x_{k-1} + R_{k-1} + D3 whatever D4 was (eqs 6 and 8).
  const ClumpParams q = extreme();
  for (int i = 0; i < 50; ++i) {
    std::mt19937_64 rng = clump_rng(5, i);
    const ClumpGeometry g = generate_clump(q, rng);
    const double d3 = q.d3 * g.central_radius;
    for (std::size_t b = 0; b < g.radii.size(); ++b) {
      if (g.origins[b].kind != BallKind::kDirection) continue;
      EXPECT_NEAR(g.centres[b].norm() + g.radii[b], g.central_radius + g.origins[b].index * d3,
                  g.central_radius * kRoundoff);
    }
  }
}

TEST(ClumpGenerator, RadiiNeverGrowAlongADirectionAndEachReductionIsWithinC) {
  for (const ClumpParams& q : all_presets_and_extreme()) {
    for (int i = 0; i < 300; ++i) {
      std::mt19937_64 rng = clump_rng(2, i);
      const ClumpGeometry g = generate_clump(q, rng);
      const auto at = direction_index(g);
      const double max_d4 = q.c * g.central_radius;
      for (const auto& [key, b] : at) {
        const int prev = key.second == 1 ? 0 : at.at({key.first, key.second - 1});
        const double d4 = g.radii[prev] - g.radii[b];
        EXPECT_GE(d4, 0.0);
        EXPECT_LE(d4, max_d4 * (1.0 + kRoundoff));
        EXPECT_GE(g.radii[b], q.min_radius_fraction * g.central_radius * (1.0 - kRoundoff));
      }
    }
  }
}

TEST(ClumpGenerator, CentreSpacingFollowsEq8) {
  // x_k = x_{k-1} + D3 + D4 along the direction, the centre staying on its axis.
  for (const ClumpParams& q : all_presets_and_extreme()) {
    const std::vector<Vec3>& dirs = candidate_directions(q.directions);
    for (int i = 0; i < 200; ++i) {
      std::mt19937_64 rng = clump_rng(3, i);
      const ClumpGeometry g = generate_clump(q, rng);
      const double d3 = q.d3 * g.central_radius;
      const auto at = direction_index(g);
      for (const auto& [key, b] : at) {
        const int prev = key.second == 1 ? 0 : at.at({key.first, key.second - 1});
        const Vec3& u = dirs[key.first];
        const double step = g.centres[b].dot(u) - g.centres[prev].dot(u);
        const double d4 = g.radii[prev] - g.radii[b];
        EXPECT_NEAR(step, d3 + d4, g.central_radius * kRoundoff);
        EXPECT_NEAR(g.centres[b].cross(u).norm(), 0.0, g.central_radius * kRoundoff);
      }
    }
  }
}

TEST(ClumpGenerator, RadiusFloorHoldsWhenReductionsWouldReachZero) {
  // n·c = 3.6 > 1: unclamped radii would go negative; clamped ones stop at the floor.
  const ClumpParams q = extreme();
  int at_floor = 0;
  for (int i = 0; i < 200; ++i) {
    std::mt19937_64 rng = clump_rng(4, i);
    const ClumpGeometry g = generate_clump(q, rng);
    for (double r : g.radii) {
      ASSERT_GE(r, q.min_radius_fraction * g.central_radius * (1.0 - kRoundoff));
      if (std::abs(r - q.min_radius_fraction * g.central_radius) < g.central_radius * 1e-12) {
        ++at_floor;
      }
    }
  }
  EXPECT_GT(at_floor, 0);
}

TEST(ClumpGenerator, EdgeBallsAreEquallySpacedWithLinearRadii) {
  for (const ClumpParams& q : all_presets_and_extreme()) {
    const int n = q.balls_per_direction, m = q.edge_balls;
    for (int i = 0; i < 200; ++i) {
      std::mt19937_64 rng = clump_rng(6, i);
      const ClumpGeometry g = generate_clump(q, rng);
      const auto at = direction_index(g);
      for (std::size_t b = 0; b < g.radii.size(); ++b) {
        if (g.origins[b].kind != BallKind::kEdge) continue;
        const int ea = at.at({g.origins[b].direction, n});
        const int eb = at.at({g.origins[b].other_direction, n});
        const double t = static_cast<double>(g.origins[b].index) / (m + 1);
        EXPECT_NEAR((g.centres[b] - ((1 - t) * g.centres[ea] + t * g.centres[eb])).norm(), 0.0,
                    g.central_radius * kRoundoff);
        EXPECT_NEAR(g.radii[b], (1 - t) * g.radii[ea] + t * g.radii[eb],
                    g.central_radius * kRoundoff);
      }
    }
  }
}

TEST(ClumpGenerator, EdgesJoinExactlyTheAdjacentUsedDirections) {
  for (const ClumpParams& q : all_presets_and_extreme()) {
    const auto pairs = adjacent_direction_pairs(q.directions, q.adjacency);
    for (int i = 0; i < 200; ++i) {
      std::mt19937_64 rng = clump_rng(7, i);
      const ClumpGeometry g = generate_clump(q, rng);
      const std::set<int> used(g.used_directions.begin(), g.used_directions.end());
      std::set<std::pair<int, int>> expected, found;
      for (auto [a, b] : pairs) {
        if (used.count(a) && used.count(b)) expected.insert({a, b});
      }
      int edge_balls = 0;
      for (const BallOrigin& o : g.origins) {
        if (o.kind != BallKind::kEdge) continue;
        found.insert({o.direction, o.other_direction});
        ++edge_balls;
      }
      EXPECT_EQ(found, expected);
      EXPECT_EQ(edge_balls, static_cast<int>(expected.size()) * q.edge_balls);
      EXPECT_EQ(static_cast<int>(g.radii.size()),
                1 + static_cast<int>(used.size()) * q.balls_per_direction + edge_balls);
    }
  }
}

TEST(ClumpGenerator, HullAdjacencyIsTheConvexHullOfTheDirections) {
  // Independent oracle: brute-force hull faces (triples with every other direction on
  // one side of their plane); edges are the pairs that bound a face.
  for (int n : {6, 14}) {
    const std::vector<Vec3>& d = candidate_directions(n);
    std::set<std::pair<int, int>> hull;
    for (int i = 0; i < n; ++i) {
      for (int j = i + 1; j < n; ++j) {
        for (int k = j + 1; k < n; ++k) {
          const Vec3 normal = (d[j] - d[i]).cross(d[k] - d[i]);
          if (normal.norm() < 1e-9) continue;
          int above = 0, below = 0;
          for (int l = 0; l < n; ++l) {
            const double side = normal.dot(d[l] - d[i]);
            above += side > 1e-9;
            below += side < -1e-9;
          }
          if (above == 0 || below == 0) hull.insert({{i, j}, {i, k}, {j, k}});
        }
      }
    }
    const auto pairs = adjacent_direction_pairs(n, EdgeAdjacency::kHull);
    const std::set<std::pair<int, int>> ours(pairs.begin(), pairs.end());
    EXPECT_EQ(ours, hull);
    EXPECT_EQ(hull.size(), n == 6 ? 12u : 36u);
  }
  EXPECT_EQ(adjacent_direction_pairs(6, EdgeAdjacency::kFaceToDiagonal).size(), 12u);
  EXPECT_EQ(adjacent_direction_pairs(14, EdgeAdjacency::kFaceToDiagonal).size(), 24u);
}

TEST(ClumpGenerator, ProbabilityZeroGivesTheCentralBallAlone) {
  for (int dirs : {6, 14}) {
    ClumpParams q = table2_sample2();
    q.directions = dirs;
    q.p = 0.0;
    for (int i = 0; i < 1000; ++i) {
      std::mt19937_64 rng = clump_rng(8, i);
      const ClumpGeometry g = generate_clump(q, rng);
      ASSERT_EQ(g.radii.size(), 1u);
      EXPECT_EQ(g.radii[0], central_ball_radius(q));
      EXPECT_EQ(g.centres[0], Vec3::Zero());
    }
  }
}

TEST(ClumpGenerator, ProbabilityOneUsesEveryDirection) {
  ClumpParams q = table2_sample2();
  q.directions = 6;
  q.p = 1.0;
  q.edge_balls = 1;
  for (int i = 0; i < 100; ++i) {
    std::mt19937_64 rng = clump_rng(9, i);
    const ClumpGeometry g = generate_clump(q, rng);
    EXPECT_EQ(g.used_directions, (std::vector<int>{0, 1, 2, 3, 4, 5}));
    EXPECT_EQ(g.radii.size(), 1u + 6u * 2u + 12u * 1u);
  }
  q.directions = 14;
  q.edge_balls = 2;
  std::mt19937_64 rng = clump_rng(9, 0);
  EXPECT_EQ(generate_clump(q, rng).radii.size(), 1u + 14u * 2u + 36u * 2u);
  q.adjacency = EdgeAdjacency::kFaceToDiagonal;
  EXPECT_EQ(generate_clump(q, rng).radii.size(), 1u + 14u * 2u + 24u * 2u);
}

TEST(ClumpGenerator, SameSeedSameClumpBitForBitAndDifferentSeedsDiffer) {
  const ClumpParams q = table2_sample2();
  for (int i = 0; i < 20; ++i) {
    std::mt19937_64 a = clump_rng(123, i), b = clump_rng(123, i), c = clump_rng(124, i);
    const ClumpGeometry ga = generate_clump(q, a), gb = generate_clump(q, b),
                        gc = generate_clump(q, c);
    ASSERT_EQ(ga.radii.size(), gb.radii.size());
    for (std::size_t k = 0; k < ga.radii.size(); ++k) {
      EXPECT_EQ(ga.radii[k], gb.radii[k]);  // exact: same bits
      EXPECT_EQ(ga.centres[k], gb.centres[k]);
    }
    EXPECT_TRUE(ga.radii != gc.radii) << "seeds 123 and 124 gave the same clump " << i;
  }
}

TEST(ClumpGenerator, UniformDrawsCoverTheirIntervals) {
  // 53-bit conversions: (0, 1] never returns 0, [0, 1) never returns 1.
  std::mt19937_64 rng(1);
  double lo = 1.0, hi = 0.0;
  for (int i = 0; i < 100000; ++i) {
    const double u = uniform_open_closed(rng), v = uniform_closed_open(rng);
    ASSERT_GT(u, 0.0);
    ASSERT_LE(u, 1.0);
    ASSERT_GE(v, 0.0);
    ASSERT_LT(v, 1.0);
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  EXPECT_LT(lo, 1e-3);
  EXPECT_GT(hi, 1.0 - 1e-3);
}

TEST(ClumpGenerator, ExpectedCountFormula) {
  // 1 + p·N·n + p²·E·m for the readings compared in docs/CLUMPS.md.
  ClumpParams s1;  // defaults are Table 2 Sample 1
  EXPECT_DOUBLE_EQ(expected_ball_count(s1), 10.0);
  ClumpParams s2 = table2_sample2();
  EXPECT_DOUBLE_EQ(expected_ball_count(s2), 33.0);
  s2.adjacency = EdgeAdjacency::kFaceToDiagonal;
  EXPECT_DOUBLE_EQ(expected_ball_count(s2), 27.0);
  EXPECT_NEAR(expected_ball_count(load_clump_preset("table1/sample4").params), 23.72, 1e-12);
  EXPECT_NEAR(expected_ball_count(load_clump_preset("table1/sample5").params), 25.96, 1e-12);
}

TEST(ClumpGenerator, SampleMeansMatchTheExpectedCount) {
  for (const std::string& name : available_clump_presets()) {
    const ClumpParams q = load_clump_preset(name).params;
    const int count = 4000;
    double sum = 0.0, sum2 = 0.0;
    for (int i = 0; i < count; ++i) {
      std::mt19937_64 rng = clump_rng(17, i);
      const double n = static_cast<double>(generate_clump(q, rng).radii.size());
      sum += n;
      sum2 += n * n;
    }
    const double mean = sum / count;
    const double se = std::sqrt((sum2 / count - mean * mean) / (count - 1));
    EXPECT_NEAR(mean, expected_ball_count(q), 4.0 * se) << name;
  }
}

// The paper's balls per clump (Table 2, section 3.2) against ours: the difference of
// two sample means, with 4 combined standard errors (our sample's and the paper's,
// whose spread we take to be our sample's), i.e. a two-sided 6e-5 false-alarm rate.
void expect_matches_paper(const ClumpPreset& preset, EdgeAdjacency adjacency, bool match) {
  ClumpParams q = preset.params;
  q.adjacency = adjacency;
  const int count = 10000;
  double sum = 0.0, sum2 = 0.0;
  for (int i = 0; i < count; ++i) {
    std::mt19937_64 rng = clump_rng(1, i);
    const double n = static_cast<double>(generate_clump(q, rng).radii.size());
    sum += n;
    sum2 += n * n;
  }
  const double mean = sum / count;
  const double var = (sum2 / count - mean * mean) * count / (count - 1);
  const double paper = static_cast<double>(*preset.paper_balls) / *preset.paper_clumps;
  const double tolerance = 4.0 * std::sqrt(var / count + var / *preset.paper_clumps);
  if (match) {
    EXPECT_NEAR(mean, paper, tolerance) << preset.name;
  } else {
    EXPECT_GT(std::abs(mean - paper), tolerance) << preset.name;
  }
}

TEST(ClumpGenerator, Table2BallsPerClumpMatchThePaper) {
  const ClumpPreset s1 = load_clump_preset("table2/sample1");
  const ClumpPreset s2 = load_clump_preset("table2/sample2");
  ASSERT_TRUE(s1.paper_clumps && s2.paper_clumps);
  expect_matches_paper(s1, EdgeAdjacency::kHull, true);  // 9.97 = 17,642 / 1,770
  expect_matches_paper(s2, EdgeAdjacency::kHull, true);  // 32.9 = 65,591 / 1,995
  // The alternative reading that fits Fig. 7 (27 balls) is ruled out by Table 2.
  expect_matches_paper(s2, EdgeAdjacency::kFaceToDiagonal, false);
}

// Throws std::invalid_argument whose message names the field.
void expect_rejected(const ClumpParams& q, const std::string& field) {
  const std::string quoted = "'" + field + "'";
  expect_error<std::invalid_argument>([&] { validate_clump_params(q); }, {quoted.c_str()});
}

TEST(ClumpGenerator, BadParametersAreRejectedNamingTheField) {
  const ClumpParams ok = table2_sample2();
  EXPECT_NO_THROW(validate_clump_params(ok));
  auto with = [&ok](auto change) {
    ClumpParams q = ok;
    change(q);
    return q;
  };
  expect_rejected(with([](ClumpParams& q) { q.directions = 8; }), "directions");
  expect_rejected(with([](ClumpParams& q) { q.p = 1.5; }), "p");
  expect_rejected(with([](ClumpParams& q) { q.p = -0.01; }), "p");
  expect_rejected(with([](ClumpParams& q) { q.p = NAN; }), "p");
  expect_rejected(with([](ClumpParams& q) { q.balls_per_direction = -1; }), "balls_per_direction");
  expect_rejected(with([](ClumpParams& q) { q.c = 1.0; }), "c");
  expect_rejected(with([](ClumpParams& q) { q.c = -0.1; }), "c");
  expect_rejected(with([](ClumpParams& q) { q.d3 = -0.2; }), "d3");
  expect_rejected(with([](ClumpParams& q) { q.edge_balls = -2; }), "edge_balls");
  expect_rejected(with([](ClumpParams& q) { q.nominal_diameter = 0.0; }), "nominal_diameter");
  expect_rejected(with([](ClumpParams& q) { q.virtual_sphere_factor = -1.0; }),
                  "virtual_sphere_factor");
  expect_rejected(with([](ClumpParams& q) { q.min_radius_fraction = 0.0; }), "min_radius_fraction");
  expect_rejected(with([](ClumpParams& q) { q.min_radius_fraction = 1.0; }), "min_radius_fraction");
  // The message also says what is allowed, from the parameter table.
  expect_error<std::invalid_argument>(
      [&] { validate_clump_params(with([](ClumpParams& q) { q.p = 1.5; })); },
      {"clump parameter 'p' = 1.5 is not allowed (allowed: in [0, 1])"});
  expect_error<std::invalid_argument>(
      [&] { validate_clump_params(with([](ClumpParams& q) { q.c = 1.0; })); },
      {"clump parameter 'c' = 1 is not allowed (allowed: in [0, 1) (fraction of R))"});
  // n·D3 at most 1/min_radius_fraction − 1 = 19 (n = 2, min_radius_fraction 0.05): the
  // central ball, Rv / (1 + n·D3), stays at least 5 % of the virtual sphere.
  EXPECT_NO_THROW(validate_clump_params(with([](ClumpParams& q) { q.d3 = 9.5; })));
  expect_error<std::invalid_argument>(
      [&] { validate_clump_params(with([](ClumpParams& q) { q.d3 = 9.6; })); },
      {"clump parameter 'd3' = 9.6 is too large with balls_per_direction = 2 (allowed: d3 <= 9.5"});
}

TEST(ClumpPresets, UnknownPresetListsTheAvailableOnes) {
  expect_error<std::invalid_argument>([] { load_clump_preset("table3/sample1"); },
                                      {"'table3/sample1'", "table1/sample1", "table2/sample2"});
}

TEST(ClumpPresets, PresetsHoldThePapersTables) {
  const ClumpParams s4 = load_clump_preset("table1/sample4").params;
  EXPECT_EQ(s4.directions, 14);
  EXPECT_EQ(s4.p, 0.4);
  EXPECT_EQ(s4.balls_per_direction, 2);
  EXPECT_EQ(s4.c, 0.4);
  EXPECT_EQ(s4.d3, 0.2);
  EXPECT_EQ(s4.edge_balls, 2);
  const ClumpPreset t2 = load_clump_preset("table2/sample2");
  EXPECT_EQ(t2.params.virtual_sphere_factor, 1.31);
  EXPECT_EQ(t2.params.nominal_diameter, 0.03625);
  EXPECT_EQ(t2.density, 2600.0);
  EXPECT_EQ(*t2.paper_clumps, 1995);
  EXPECT_EQ(*t2.paper_balls, 65591);
}

void expect_parse_error(const std::string& json, const std::string& needle) {
  expect_error<std::invalid_argument>([&] { parse_clump_preset(json, "test.json"); },
                                      {needle, "test.json"});
}

TEST(ClumpPresets, BadFieldsAreRejectedNamingTheField) {
  const std::string base =
      R"("directions": 6, "balls_per_direction": 2, "c": 0.2, "d3": 0.2, "edge_balls": 1, )"
      R"("virtual_sphere_factor": 1.26)";
  EXPECT_NO_THROW(parse_clump_preset("{" + base + R"(, "p": 0.5})", "test.json"));
  expect_parse_error("{" + base + R"(, "p": 1.5})", "/p = 1.5 (allowed: a number in [0, 1])");
  expect_parse_error("{" + base + R"(, "p": "half"})", "/p = \"half\"");
  expect_parse_error("{" + base + R"(, "p": 0.5, "pp": 0.5})", "unknown field 'pp'");
  expect_parse_error("{" + base + "}", "missing field 'p'");
  expect_parse_error("{" + base + R"(, "p": 0.5, "adjacency": "ring"})", "/adjacency = \"ring\"");
  expect_parse_error("{" + base + R"(, "p": 0.5, "density": -1})", "/density = -1");
  expect_parse_error(R"({"directions": 6.5, "p": 0.5, "balls_per_direction": 2, "c": 0.2, )"
                     R"("d3": 0.2, "edge_balls": 1, "virtual_sphere_factor": 1.26})",
                     "/directions = 6.5");
  expect_parse_error("{" + base + R"(, "p": 0.5, "paper": {"clumps": 10, "balls": 5}})",
                     "/paper/balls = 5");
  expect_parse_error("[1, 2]", "object");
  expect_parse_error("{ not json", "JSON");
}

}  // namespace
}  // namespace ballast
