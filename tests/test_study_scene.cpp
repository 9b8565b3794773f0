// What a study run runs (study/matrix/study_scene.hpp, study/matrix/study_plan.hpp): its parameters
// on the scene's keys, its clump exactly as docs/STUDY.md resolves it, its seed in
// full; the scene's own refusals with the run named; shards; jobs x threads.
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "cases/clump_presets.hpp"
#include "study/matrix/run_identity.hpp"
#include "study/matrix/study_json.hpp"
#include "study/matrix/study_keys.hpp"
#include "study/matrix/study_plan.hpp"
#include "study/matrix/study_scene.hpp"
#include "study_text.hpp"
#include "test_helpers.hpp"

namespace ballast {
namespace {

using nlohmann::json;

const json kBase = json::parse(R"({
  "name": "base",
  "particles": {"shape": "table1/sample3", "count": 40, "seed": 1,
                "clump": {"c": 0.4}},
  "box": {"length": 0.2, "width": 0.12},
  "sleeper": {"cycles": 1, "length": 0.1}})");

StudySpec expand(const std::string& matrix) {
  return study_text::expand(study_text::with_matrix(matrix));
}

void expect_same_clump(const ClumpParams& a, const ClumpParams& b) {
  EXPECT_EQ(a.directions, b.directions);
  EXPECT_EQ(a.p, b.p);
  EXPECT_EQ(a.balls_per_direction, b.balls_per_direction);
  EXPECT_EQ(a.c, b.c);
  EXPECT_EQ(a.d3, b.d3);
  EXPECT_EQ(a.edge_balls, b.edge_balls);
  EXPECT_EQ(a.adjacency, b.adjacency);
  EXPECT_EQ(a.virtual_sphere_factor, b.virtual_sphere_factor);
  EXPECT_EQ(a.min_radius_fraction, b.min_radius_fraction);
  EXPECT_EQ(a.nominal_diameter, b.nominal_diameter);
}

TEST(StudyScene, EveryStudyKeyHasASceneKey) {
  std::set<std::string> mapped;
  for (const SceneKey& k : scene_keys()) mapped.insert(std::string(k.study_key));
  for (const StudyKey& k : study_keys()) EXPECT_TRUE(mapped.count(std::string(k.name))) << k.name;
  EXPECT_EQ(mapped.size(), study_keys().size());
}

// A study key's range and its scene key's must agree at every finite bound: a
// closed bound the study allows, the scene allows; just past a bound both refuse; a
// key the study leaves unbounded above, the scene takes up to a million (the study's
// gravity_factor >= 1 against the scene's [1, 1000] fails here), or, for a fixed dt
// and the frequency, which the scene bounds together (cases/scene_bounds.cpp: 20
// steps a cycle), up to a millisecond and 100 Hz. The count is left out: the scene bounds it by the
// box's size, not by a number.
TEST(StudyScene, StudyAndSceneRangesAgreeAtTheirBounds) {
  const auto scene_allows = [](const SceneKey& key, double v) {
    json scene = kBase;
    scene["particles"] = {{"shape", "spheres"}, {"count", 40}};
    json value = v;
    if (find_study_key(key.study_key)->kind == KeyKind::kInteger) value = std::llround(v);
    scene[json::json_pointer(std::string(key.scene_pointer))] = value;
    try {
      parse_box_test_scene(scene);
      return true;
    } catch (const SetupError&) {
      return false;
    }
  };
  for (const SceneKey& key : scene_keys()) {
    const StudyKey* k = find_study_key(key.study_key);
    if (k->group == "clump" || k->name == "count" || k->range.lo == -INFINITY) continue;
    if (k->kind != KeyKind::kNumber && k->kind != KeyKind::kInteger) continue;
    SCOPED_TRACE(std::string(k->name));
    const KeyRange& r = k->range;
    const double step = k->kind == KeyKind::kInteger ? 1.0 : 1e-9 * std::max(1.0, std::abs(r.lo));
    if (!r.lo_open) {
      EXPECT_TRUE(scene_allows(key, r.lo));
    }
    EXPECT_FALSE(scene_allows(key, r.lo - (r.lo_open ? 0.0 : step)));
    if (r.hi == INFINITY) {  // unbounded above: the scene too, as far as a million
      // ... or as far as the bounds that tie fields together allow (cases/scene_bounds):
      // a 1e6 N/m ball carries less than the peak load at an overlap of its radius, and
      // a floor 0.12 m wide and 0.46 m long or more is not covered by 40 spheres.
      const double far = k->name == "dt"               ? 1e-3
                         : k->name == "frequency"      ? 100.0
                         : k->name == "box_length"     ? 0.4
                         : k->name == "ball_stiffness" ? 1e12
                         : k->name == "wall_stiffness" ? 1e12
                                                       : 1e6;
      EXPECT_TRUE(scene_allows(key, far));
      continue;
    }
    const double hi_step = k->kind == KeyKind::kInteger ? 1.0 : 1e-9 * std::max(1.0, r.hi);
    if (!r.hi_open) {
      EXPECT_TRUE(scene_allows(key, r.hi));
    }
    EXPECT_FALSE(scene_allows(key, r.hi + (r.hi_open ? 0.0 : hi_step)));
  }
}

TEST(StudyScene, NumericsAndLoadingKeysLandOnTheirSceneKeys) {
  const StudySpec s = expand(R"({"axes": {"dt_safety": [0.4], "rotation": ["full"],
    "mass_mode": ["uniform"], "local_damping": [0.3], "gravity_factor": [20], "cycles": [3],
    "frequency": [10]}})");
  const json scene = run_scene_json(kBase, s.runs[0]);
  EXPECT_EQ(scene["numerics"]["dt_safety"], 0.4);
  EXPECT_EQ(scene["numerics"]["rotation"], "full");
  EXPECT_EQ(scene["particles"]["mass_mode"], "uniform");
  EXPECT_EQ(scene["numerics"]["local_damping"], 0.3);
  EXPECT_EQ(scene["preparation"]["gravity_factor"], 20.0);
  EXPECT_EQ(scene["sleeper"]["cycles"], 3);
  EXPECT_EQ(scene["sleeper"]["frequency"], 10);
  // No clump key: the base scene's particles stay as they are.
  EXPECT_EQ(scene["particles"]["shape"], "table1/sample3");
  EXPECT_EQ(scene["particles"]["clump"]["c"], 0.4);
  const BoxTestScene b = parse_run_scene(scene, s.runs[0], "t.json", "s.json");
  EXPECT_EQ(b.sim.dt_safety, 0.4);
  EXPECT_EQ(b.sim.rotation, RotationIntegrator::kFull);
  EXPECT_EQ(b.mass_mode, MassMode::kUniform);
  EXPECT_EQ(b.cycles, 3);
}

// The contact law as a study factor: the run's scene names it, and the box test's
// materials carry both laws' parameters, so the base scene needs no other change.
TEST(StudyScene, TheContactLawIsAFactorOfItsOwn) {
  const StudySpec s = expand(R"({"axes": {"contact_law": ["linear", "hertz_mindlin"]}})");
  ASSERT_EQ(s.runs.size(), 2u);
  const BoxTestScene linear =
      parse_run_scene(run_scene_json(kBase, s.runs[0]), s.runs[0], "t.json", "s.json");
  const BoxTestScene hertz =
      parse_run_scene(run_scene_json(kBase, s.runs[1]), s.runs[1], "t.json", "s.json");
  EXPECT_EQ(linear.sim.contact_law, "linear");
  EXPECT_EQ(hertz.sim.contact_law, "hertz_mindlin");
  EXPECT_GT(hertz.ball.young_modulus, 0.0);
  test_support::expect_error([] { expand(R"({"axes": {"contact_law": ["hertz"]}})"); },
                             {"contact_law", "\"hertz\"", "\"linear\" or \"hertz_mindlin\""});
}

TEST(StudyScene, TheRunsSeedIsTheScenesSeedInFull64Bits) {
  RunSpec run;
  run.id = "r1";
  run.params = json::object();
  run.seed = 0xfedcba9876543210ULL;  // above INT64_MAX
  const BoxTestScene b = parse_run_scene(run_scene_json(kBase, run), run, "t.json", "s.json");
  EXPECT_EQ(b.seed, 0xfedcba9876543210ULL);
}

TEST(StudyScene, TheRunsClumpIsExactlyWhatTheStudyResolves) {
  // A shape with overrides, n for p, clump parameters without a shape.
  const StudySpec s = expand(R"({"samples": [
      {"name": "a", "shape": "table2/sample2", "c": 0.1, "edge_balls": 0},
      {"name": "b", "shape": "table1/sample1", "n": 3},
      {"name": "c", "d3": 0.3, "adjacency": "face_to_diagonal"}]})");
  for (const RunSpec& run : s.runs) {
    SCOPED_TRACE(run.id);
    const json scene = run_scene_json(kBase, run);
    const BoxTestScene b = parse_run_scene(scene, run, "t.json", "s.json");
    ASSERT_TRUE(b.clumps.has_value());
    ClumpParams expected = resolve_run_clump(run.params)->params;
    expected.nominal_diameter = b.diameter;  // the scene's particle size
    expect_same_clump(*b.clumps, expected);
  }
  // The base scene's own clump override (c = 0.4) does not leak into a run that
  // brings its clump.
  EXPECT_FALSE(run_scene_json(kBase, s.runs[1])["particles"]["clump"].contains("c"));
  EXPECT_EQ(run_scene_json(kBase, s.runs[1])["particles"]["clump"]["p"], 3.0 / 6.0);
}

TEST(StudyScene, DefaultClumpShapeIsClumpParamsDefaults) {
  // A run with clump parameters and no shape starts from ClumpParams' defaults
  // (docs/STUDY.md); the scene gets shape table2/sample1, which must be those.
  ClumpParams preset = load_clump_preset("table2/sample1").params;
  expect_same_clump(preset, ClumpParams{});
}

TEST(StudyScene, SpheresDropTheBaseScenesClump) {
  const StudySpec s = expand(R"({"samples": [{"name": "s", "shape": "spheres"}]})");
  const json scene = run_scene_json(kBase, s.runs[0]);
  EXPECT_EQ(scene["particles"]["shape"], "spheres");
  EXPECT_FALSE(scene["particles"].contains("clump"));
  EXPECT_FALSE(parse_run_scene(scene, s.runs[0], "t.json", "s.json").clumps.has_value());
}

TEST(StudyScene, AValueTheSceneRefusesNamesTheRunAndTheScenePath) {
  // The study allows any count >= 1; the scene refuses one that its box cannot hold.
  const StudySpec s = expand(R"({"axes": {"count": [100000]}})");
  test_support::expect_error<StudyError>(
      [&] { parse_run_scene(run_scene_json(kBase, s.runs[0]), s.runs[0], "t.json", "s.json"); },
      {"t.json: run 'count=100000-r1'", "/particles/count = 100000", "1.8 box heights"});
}

TEST(StudyPlan, ShardsPartitionTheRuns) {
  const StudySpec s = expand(R"({"replicates": 10})");
  std::multiset<std::size_t> seen;
  for (int k = 1; k <= 3; ++k) {
    for (const RunSpec* r : shard_runs(s, parse_shard(std::to_string(k) + "/3"))) {
      EXPECT_EQ(r->index % 3, static_cast<std::size_t>(k - 1));
      seen.insert(r->index);
    }
  }
  EXPECT_EQ(seen.size(), 10u);
  EXPECT_EQ(std::set<std::size_t>(seen.begin(), seen.end()).size(), 10u);  // each once
  EXPECT_EQ(shard_runs(s, Shard{}).size(), 10u);
}

TEST(StudyPlan, BadShardsAreRefused) {
  for (const char* bad : {"0/2", "3/2", "1/0", "1", "a/b", "1/2/3", "-1/2", "1/200000", ""}) {
    EXPECT_THROW(parse_shard(bad), SetupError) << bad;
  }
  EXPECT_EQ(parse_shard("2/5").index, 2);
  EXPECT_EQ(parse_shard("2/5").count, 5);
}

TEST(StudyPlan, RunsSideBySideFirstThenThreads) {
  const auto plan = [](int cores, std::size_t runs, int jobs, int threads) {
    const Parallelism p = plan_parallelism(cores, runs, jobs, threads);
    return std::make_pair(p.jobs, p.threads);
  };
  EXPECT_EQ(plan(2, 3, 0, 0), std::make_pair(2, 1));  // the brief's example
  EXPECT_EQ(plan(16, 3, 0, 0), std::make_pair(3, 5));
  EXPECT_EQ(plan(16, 100, 0, 0), std::make_pair(16, 1));
  EXPECT_EQ(plan(8, 1, 0, 0), std::make_pair(1, 8));
  EXPECT_EQ(plan(8, 0, 0, 0), std::make_pair(1, 8));   // nothing left to run
  EXPECT_EQ(plan(8, 10, 2, 0), std::make_pair(2, 4));  // --jobs 2
  EXPECT_EQ(plan(8, 10, 0, 4), std::make_pair(2, 4));  // --threads 4
  EXPECT_EQ(plan(2, 10, 0, 4), std::make_pair(1, 4));  // more threads than cores: asked for
  EXPECT_EQ(plan(2, 10, 3, 3), std::make_pair(3, 3));  // both: as given
  EXPECT_EQ(plan(8, 2, 4, 0), std::make_pair(2, 2));   // never more jobs than runs
}

}  // namespace
}  // namespace ballast
