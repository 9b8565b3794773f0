// A study file expanded into runs (study/matrix/study_matrix.hpp, docs/STUDY.md): how many
// runs, in which order, with which parameters, ids and seeds, and that ids and seeds
// stay put when unrelated runs are added. Bad input: tests/test_study_errors.cpp.
#include <gtest/gtest.h>

#include <map>
#include <set>
#include <string>

#include "study/matrix/run_identity.hpp"
#include "study/matrix/study_json.hpp"
#include "study/matrix/study_matrix.hpp"
#include "study_text.hpp"

namespace ballast {
namespace {

// A study with the given "matrix" object (JSON text).
StudySpec expand(const std::string& matrix, std::uint64_t seed = 2007) {
  return study_text::expand(study_text::with_matrix(matrix, "box_test/smoke.json", seed));
}

std::vector<std::string> ids(const StudySpec& s) {
  std::vector<std::string> out;
  for (const RunSpec& r : s.runs) out.push_back(r.id);
  return out;
}

std::map<std::string, std::uint64_t> seeds_by_id(const StudySpec& s) {
  std::map<std::string, std::uint64_t> out;
  for (const RunSpec& r : s.runs) out[r.id] = r.seed;
  return out;
}

const char* const kProduct = R"({
  "axes": {"rotation": ["pfc", "full"], "dt_safety": [0.8, 0.4, 0.2]},
  "samples": [{"name": "spheres", "shape": "spheres"}, {"name": "T2S1", "shape": "table2/sample1"}],
  "replicates": 3})";

TEST(StudyMatrix, ProductOfAxesSamplesAndReplicates) {
  const StudySpec s = expand(kProduct);
  EXPECT_EQ(s.name, "t");
  EXPECT_EQ(s.scene, "box_test/smoke.json");
  EXPECT_EQ(s.seed, 2007u);
  ASSERT_EQ(s.runs.size(), 2u * 3u * 2u * 3u);  // 36
  for (std::size_t i = 0; i < s.runs.size(); ++i) EXPECT_EQ(s.runs[i].index, i);
}

TEST(StudyMatrix, OrderIsSamplesThenAxesAsWrittenThenReplicates) {
  const StudySpec s = expand(kProduct);
  // rotation is written before dt_safety, so it is the outer of the two although it
  // sorts after it.
  EXPECT_EQ(s.runs[0].id, "spheres-dt_safety=0.8-rotation=pfc-r1");
  EXPECT_EQ(s.runs[1].id, "spheres-dt_safety=0.8-rotation=pfc-r2");
  EXPECT_EQ(s.runs[2].id, "spheres-dt_safety=0.8-rotation=pfc-r3");
  EXPECT_EQ(s.runs[3].id, "spheres-dt_safety=0.4-rotation=pfc-r1");
  EXPECT_EQ(s.runs[9].id, "spheres-dt_safety=0.8-rotation=full-r1");
  EXPECT_EQ(s.runs[18].id, "T2S1-dt_safety=0.8-rotation=pfc-r1");
  EXPECT_EQ(s.runs[35].id, "T2S1-dt_safety=0.2-rotation=full-r3");
  EXPECT_EQ(s.runs[35].sample, "T2S1");
  EXPECT_EQ(s.runs[35].replicate, 3);
  // Sorted-key JSON loses the order written: axes then nest alphabetically.
  const StudySpec sorted = expand_study(nlohmann::json(s.source), study_text::kFile);
  EXPECT_EQ(sorted.runs[3].id, "spheres-dt_safety=0.8-rotation=full-r1");
}

TEST(StudyMatrix, ParamsHoldEveryKeyOfTheRunInCanonicalForm) {
  const StudySpec s = expand(R"({
    "axes": {"p": [1, 0.5]},
    "samples": [{"name": "custom", "directions": 14, "c": 0, "adjacency": "face_to_diagonal"}]})");
  ASSERT_EQ(s.runs.size(), 2u);
  const nlohmann::json& q = s.runs[0].params;
  EXPECT_EQ(q.size(), 4u);
  EXPECT_TRUE(q.at("p").is_number_float());  // written 1, a number key: stored as 1.0
  EXPECT_TRUE(q.at("c").is_number_float());
  EXPECT_TRUE(q.at("directions").is_number_integer());
  EXPECT_EQ(q.at("adjacency"), "face_to_diagonal");
  EXPECT_EQ(s.runs[0].id, "custom-p=1.0-r1");
  // 1 and 1.0 are the same value: same params, same seed.
  EXPECT_EQ(s.runs[0].seed, expand(R"({"axes": {"p": [1.0, 0.5]},
    "samples": [{"name": "custom", "directions": 14, "c": 0.0, "adjacency": "face_to_diagonal"}]})")
                                .runs[0]
                                .seed);
}

TEST(StudyMatrix, ZipGroupsVaryTogetherAndCombineByProduct) {
  const StudySpec one = expand(R"({
    "axes": {"rotation": ["pfc", "full"]},
    "zip": [{"p": [0.3, 0.5, 0.7], "balls_per_direction": [1, 2, 3]}]})");
  ASSERT_EQ(one.runs.size(), 2u * 3u);
  EXPECT_EQ(one.runs[0].id, "balls_per_direction=1-p=0.3-rotation=pfc-r1");
  EXPECT_EQ(one.runs[2].id, "balls_per_direction=3-p=0.7-rotation=pfc-r1");
  for (const RunSpec& r : one.runs) {  // rows never mix
    EXPECT_DOUBLE_EQ(r.params.at("p").get<double>(),
                     0.1 + 0.2 * r.params.at("balls_per_direction").get<int>());
  }
  const StudySpec two = expand(R"({
    "zip": [{"p": [0.3, 0.5], "balls_per_direction": [1, 2]},
            {"c": [0.1, 0.2, 0.3], "d3": [0.1, 0.2, 0.3]}],
    "seeds": [4, 5]})");
  ASSERT_EQ(two.runs.size(), 2u * 3u * 2u);
  EXPECT_EQ(two.runs[0].id, "balls_per_direction=1-c=0.1-d3=0.1-p=0.3-r4");
  EXPECT_EQ(two.runs[1].id, "balls_per_direction=1-c=0.1-d3=0.1-p=0.3-r5");
  EXPECT_EQ(two.runs[2].id, "balls_per_direction=1-c=0.2-d3=0.2-p=0.3-r4");
}

TEST(StudyMatrix, ExplicitSampleList) {
  const StudySpec s = expand(R"({"samples": [
      {"name": "spheres", "shape": "spheres"},
      {"name": "T2S1", "shape": "table2/sample1"},
      {"name": "custom", "directions": 14, "n": 7, "balls_per_direction": 1}]})");
  ASSERT_EQ(s.runs.size(), 3u);
  EXPECT_EQ(ids(s), (std::vector<std::string>{"spheres-r1", "T2S1-r1", "custom-r1"}));
  EXPECT_EQ(s.runs[1].params, nlohmann::json({{"shape", "table2/sample1"}}));
  EXPECT_FALSE(resolve_run_clump(s.runs[0].params).has_value());  // spheres: no clump
  const auto t2s1 = resolve_run_clump(s.runs[1].params);
  ASSERT_TRUE(t2s1.has_value());
  EXPECT_EQ(t2s1->name, "table2/sample1");
  const auto custom = resolve_run_clump(s.runs[2].params);
  ASSERT_TRUE(custom.has_value());
  EXPECT_EQ(custom->params.directions, 14);
  EXPECT_DOUBLE_EQ(custom->params.p, 0.5);  // n / directions
  EXPECT_EQ(custom->params.balls_per_direction, 1);
}

// Spheres next to a sweep of clump parameters: the spheres are not multiplied by the
// dimensions made only of clump parameters (they would be the same run under new ids).
TEST(StudyMatrix, SpheresSkipClumpOnlyDimensions) {
  const StudySpec s = expand(R"({
    "axes": {"rotation": ["pfc", "full"], "dt_safety": [0.8, 0.4]},
    "zip": [{"c": [0.3, 0.5], "balls_per_direction": [1, 2]}],
    "samples": [{"name": "spheres", "shape": "spheres"},
                {"name": "T2S1", "shape": "table2/sample1"},
                {"name": "custom", "directions": 14, "p": 0.5}],
    "replicates": 3})");
  std::map<std::string, int> per_sample;
  for (const RunSpec& r : s.runs) ++per_sample[r.sample];
  EXPECT_EQ(per_sample["spheres"], 2 * 2 * 3);
  EXPECT_EQ(per_sample["T2S1"], 2 * 2 * 2 * 3);
  EXPECT_EQ(per_sample["custom"], 2 * 2 * 2 * 3);
  EXPECT_EQ(s.runs.size(), 60u);
  EXPECT_EQ(s.runs[0].id, "spheres-dt_safety=0.8-rotation=pfc-r1");
  EXPECT_EQ(s.runs[3].id, "spheres-dt_safety=0.4-rotation=pfc-r1");
  EXPECT_EQ(s.runs[12].id, "T2S1-balls_per_direction=1-c=0.3-dt_safety=0.8-rotation=pfc-r1");
  EXPECT_FALSE(s.runs[0].params.contains("c"));
  // A shape axis: only its clump values take the clump sweep.
  const StudySpec axis = expand(R"({
    "axes": {"shape": ["spheres", "table2/sample1"], "adjacency": ["hull", "face_to_diagonal"]}})");
  EXPECT_EQ(ids(axis),
            (std::vector<std::string>{"shape=spheres-r1", "adjacency=hull-shape=table2_sample1-r1",
                                      "adjacency=face_to_diagonal-shape=table2_sample1-r1"}));
}

TEST(StudyMatrix, PresetFieldsAreOverriddenByExplicitParameters) {
  const StudySpec s = expand(R"({"axes": {"shape": ["table2/sample2"], "c": [0.1]}})");
  ASSERT_EQ(s.runs.size(), 1u);
  EXPECT_EQ(s.runs[0].id, "c=0.1-shape=table2_sample2-r1");  // '/' is not file-name safe
  const auto clump = resolve_run_clump(s.runs[0].params);
  ASSERT_TRUE(clump.has_value());
  EXPECT_EQ(clump->params.directions, 14);  // from the preset
  EXPECT_DOUBLE_EQ(clump->params.c, 0.1);   // overridden (the preset has 0.5)
}

TEST(StudyMatrix, EmptyMatrixIsOneRun) {
  const StudySpec s = expand("{}");
  ASSERT_EQ(s.runs.size(), 1u);
  EXPECT_EQ(s.runs[0].id, "r1");
  EXPECT_TRUE(s.runs[0].params.empty());
}

TEST(StudyMatrix, IdsAndSeedsStayWhenUnrelatedRunsAreAdded) {
  const StudySpec base = expand(kProduct);
  const std::map<std::string, std::uint64_t> before = seeds_by_id(base);
  ASSERT_EQ(before.size(), base.runs.size());  // ids unique
  const char* const kGrown[] = {
      // one more axis value
      R"({"axes": {"rotation": ["pfc", "full"], "dt_safety": [0.8, 0.4, 0.2, 0.1]},
          "samples": [{"name": "spheres", "shape": "spheres"},
                      {"name": "T2S1", "shape": "table2/sample1"}], "replicates": 3})",
      // one more sample, first
      R"({"axes": {"rotation": ["pfc", "full"], "dt_safety": [0.8, 0.4, 0.2]},
          "samples": [{"name": "T2S2", "shape": "table2/sample2"},
                      {"name": "spheres", "shape": "spheres"},
                      {"name": "T2S1", "shape": "table2/sample1"}], "replicates": 3})",
      // more replicates
      R"({"axes": {"rotation": ["pfc", "full"], "dt_safety": [0.8, 0.4, 0.2]},
          "samples": [{"name": "spheres", "shape": "spheres"},
                      {"name": "T2S1", "shape": "table2/sample1"}], "replicates": 5})",
      // axes written in the other order
      R"({"axes": {"dt_safety": [0.8, 0.4, 0.2], "rotation": ["pfc", "full"]},
          "samples": [{"name": "spheres", "shape": "spheres"},
                      {"name": "T2S1", "shape": "table2/sample1"}], "replicates": 3})",
  };
  for (const char* grown_text : kGrown) {
    const std::map<std::string, std::uint64_t> after = seeds_by_id(expand(grown_text));
    for (const auto& [id, seed] : before) {
      ASSERT_TRUE(after.count(id)) << id << " lost in " << grown_text;
      EXPECT_EQ(after.at(id), seed) << id;
    }
  }
}

TEST(StudyMatrix, IdsAndSeedsStayWhenZipRowsOrReplicateNumbersAreAdded) {
  const StudySpec base = expand(R"({
    "zip": [{"p": [0.3, 0.5], "balls_per_direction": [1, 2]}, {"c": [0.1, 0.2]}],
    "seeds": [1, 2]})");
  const std::map<std::string, std::uint64_t> before = seeds_by_id(base);
  ASSERT_EQ(before.size(), 8u);
  const StudySpec grown = expand(R"({
    "zip": [{"c": [0.1, 0.2, 0.3]}, {"balls_per_direction": [1, 2, 3], "p": [0.3, 0.5, 0.7]}],
    "seeds": [7, 2, 1]})");
  ASSERT_EQ(grown.runs.size(), 27u);
  const std::map<std::string, std::uint64_t> after = seeds_by_id(grown);
  for (const auto& [id, seed] : before) {
    ASSERT_TRUE(after.count(id)) << id;
    EXPECT_EQ(after.at(id), seed) << id;
  }
}

TEST(StudyMatrix, SeedsAreDistinctReproducibleAndFollowTheStudySeed) {
  const StudySpec a = expand(kProduct);
  std::set<std::uint64_t> distinct;
  for (const RunSpec& r : a.runs) distinct.insert(r.seed);
  EXPECT_EQ(distinct.size(), a.runs.size());
  EXPECT_EQ(seeds_by_id(expand(kProduct)), seeds_by_id(a));
  const StudySpec b = expand(kProduct, 2008);
  for (std::size_t i = 0; i < a.runs.size(); ++i) {
    EXPECT_EQ(a.runs[i].id, b.runs[i].id);
    EXPECT_NE(a.runs[i].seed, b.runs[i].seed);
  }
}

// The scheme is part of the file format: results already on disk were produced with
// these seeds. The value was cross-checked with an independent Python implementation
// of docs/STUDY.md ("Ids and seeds").
TEST(StudyMatrix, SeedSchemeIsFixed) {
  const nlohmann::json params = {
      {"dt_safety", 0.4}, {"rotation", "full"}, {"shape", "table2/sample1"}};
  EXPECT_EQ(canonical_run_text(params, 1),
            R"({"params":{"dt_safety":0.4,"rotation":"full","shape":"table2/sample1"},)"
            R"("replicate":1})");
  EXPECT_EQ(fnv1a64(""), 0xcbf29ce484222325ULL);
  EXPECT_EQ(fnv1a64("a"), 0xaf63dc4c8601ec8cULL);
  EXPECT_EQ(splitmix64(0), 0xe220a8397b1dcdafULL);
  EXPECT_EQ(run_seed(2007, params, 1), 0x76369b1fda547291ULL);
  const StudySpec s = expand(R"({"axes": {"rotation": ["full"], "dt_safety": [0.4]},
    "samples": [{"name": "T2S1", "shape": "table2/sample1"}]})");
  EXPECT_EQ(s.runs[0].id, "T2S1-dt_safety=0.4-rotation=full-r1");
  EXPECT_EQ(s.runs[0].seed, run_seed(2007, params, 1));
}

// With "common_seeds" replicate k of every sample starts from one seed, the one of a
// run with no parameters; without it two samples' replicate k differ.
TEST(StudyMatrix, CommonSeedsGiveEverySampleTheReplicatesSeed) {
  const std::string samples = R"("samples": [{"name": "ref", "shape": "table2/sample1"},
    {"name": "fast", "shape": "table2/sample1", "dt_safety": 1.0}], "replicates": 2)";
  const StudySpec common = expand("{" + samples + R"(, "common_seeds": true})");
  const StudySpec own = expand("{" + samples + "}");
  ASSERT_EQ(common.runs.size(), 4u);
  for (int r = 0; r < 2; ++r) {
    EXPECT_EQ(common.runs[r].seed, run_seed(2007, nlohmann::json::object(), r + 1));
    EXPECT_EQ(common.runs[2 + r].seed, common.runs[r].seed);
    EXPECT_EQ(own.runs[r].seed, run_seed(2007, own.runs[r].params, r + 1));
    EXPECT_NE(own.runs[2 + r].seed, own.runs[r].seed);
  }
  EXPECT_NE(common.runs[0].seed, common.runs[1].seed);
}

TEST(StudyMatrix, ExampleStudiesExpand) {
  const StudySpec def = load_study_file(std::string(BALLAST_CASES_DIR) + "/default_study.json");
  EXPECT_EQ(def.name, "default");
  EXPECT_EQ(def.scene, "box_test/smoke.json");
  EXPECT_EQ(def.scene_path, std::string(BALLAST_CASES_DIR) + "/box_test/smoke.json");
  EXPECT_EQ(ids(def), (std::vector<std::string>{"spheres-r1", "T2S1-r1", "T2S2-r1"}));
  const StudySpec t1 = load_study_file(std::string(BALLAST_CASES_DIR) + "/table1_study.json");
  EXPECT_EQ(ids(t1),
            (std::vector<std::string>{"T1S1-r1", "T1S2-r1", "T1S3-r1", "T1S4-r1", "T1S5-r1"}));
  for (const RunSpec& r : t1.runs) EXPECT_TRUE(resolve_run_clump(r.params).has_value());
}

}  // namespace
}  // namespace ballast
