// A bad study file is refused before anything runs, with a message that gives the JSON
// Pointer of the problem, the offending value and what is allowed (docs/STUDY.md,
// "Error messages"). One test per kind of mistake.
#include <gtest/gtest.h>

#include <initializer_list>
#include <string>

#include "study/matrix/study_json.hpp"
#include "study/matrix/study_matrix.hpp"
#include "study_text.hpp"

namespace ballast {
namespace {

// Expects a StudyError at `path` whose message holds the path and every fragment.
void expect_refused(const std::string& text, const std::string& path,
                    std::initializer_list<const char*> fragments) {
  try {
    study_text::expand(text);
    ADD_FAILURE() << "accepted: " << text;
  } catch (const StudyError& e) {
    const std::string what = e.what();
    EXPECT_EQ(e.path, path) << what;
    EXPECT_EQ(what.rfind(study_text::kFile + " at " + path + ": ", 0), 0u) << what;
    for (const char* f : fragments) {
      EXPECT_NE(what.find(f), std::string::npos) << "'" << what << "' lacks '" << f << "'";
    }
  }
}

void expect_refused_matrix(const std::string& matrix, const std::string& path,
                           std::initializer_list<const char*> fragments) {
  expect_refused(study_text::with_matrix(matrix), path, fragments);
}

TEST(StudyErrors, UnknownTopLevelKey) {
  expect_refused(R"({"name": "t", "scene": "s", "sede": 1, "seed": 1, "matrix": {}})", "/sede",
                 {"unknown key \"sede\"", "allowed: name, scene, seed, matrix"});
}

TEST(StudyErrors, MissingScene) {
  expect_refused(R"({"name": "t", "seed": 1, "matrix": {}})", "/scene", {"missing key \"scene\""});
}

TEST(StudyErrors, NegativeOrFractionalStudySeed) {
  expect_refused(R"({"name": "t", "scene": "s", "seed": -3, "matrix": {}})", "/seed",
                 {"seed = -3", "unsigned integer"});
  expect_refused(R"({"name": "t", "scene": "s", "seed": 2.5, "matrix": {}})", "/seed",
                 {"seed = 2.5", "unsigned integer"});
}

TEST(StudyErrors, StudyNameNotSafeForFiles) {
  expect_refused(R"({"name": "a b", "scene": "s", "seed": 1, "matrix": {}})", "/name",
                 {"\"a b\"", "letters, digits"});
}

TEST(StudyErrors, UnknownMatrixKey) {
  expect_refused_matrix(R"({"axis": {}})", "/matrix/axis",
                        {"unknown key \"axis\"", "axes, zip, samples, replicates, seeds"});
}

TEST(StudyErrors, UnknownParameterInAxes) {
  expect_refused_matrix(R"({"axes": {"friction": [0.3]}})", "/matrix/axes/friction",
                        {"unknown key \"friction\"", "directions, p, n"});
}

TEST(StudyErrors, UnknownParameterInSample) {
  expect_refused_matrix(R"({"samples": [{"name": "a", "shape": "spheres", "P": 0.5}]})",
                        "/matrix/samples/0/P", {"unknown key \"P\"", "name, shape"});
}

TEST(StudyErrors, UnknownParameterInZipGroup) {
  expect_refused_matrix(R"({"zip": [{"p": [0.5], "ball_per_direction": [2]}]})",
                        "/matrix/zip/0/ball_per_direction",
                        {"unknown key \"ball_per_direction\"", "balls_per_direction"});
}

TEST(StudyErrors, ValueOutOfRange) {
  expect_refused_matrix(R"({"axes": {"p": [0.3, 0.5, 1.5]}})", "/matrix/axes/p/2",
                        {"p = 1.5", "out of range", "allowed: a number in [0, 1]"});
  expect_refused_matrix(R"({"axes": {"c": [1.0]}})", "/matrix/axes/c/0",
                        {"c = 1.0", "a number in [0, 1)"});
  expect_refused_matrix(R"({"axes": {"dt_safety": [0.8, 0]}})", "/matrix/axes/dt_safety/1",
                        {"dt_safety = 0", "a number in (0, 1]"});
  expect_refused_matrix(R"({"axes": {"gravity_factor": [0.5]}})", "/matrix/axes/gravity_factor/0",
                        {"gravity_factor = 0.5", "a number in [1, 1000]"});
  expect_refused_matrix(R"({"axes": {"cycles": [0]}})", "/matrix/axes/cycles/0",
                        {"cycles = 0", "an integer >= 1"});
}

TEST(StudyErrors, WrongType) {
  expect_refused_matrix(R"({"axes": {"p": [0.5, "0.7"]}})", "/matrix/axes/p/1",
                        {"p = \"0.7\"", "not a number", "a number in [0, 1]"});
  expect_refused_matrix(R"({"axes": {"rotation": [true]}})", "/matrix/axes/rotation/0",
                        {"rotation = true", "not a string", "\"pfc\" or \"full\""});
}

TEST(StudyErrors, IntegerExpected) {
  expect_refused_matrix(R"({"zip": [{"balls_per_direction": [1, 2.5]}]})",
                        "/matrix/zip/0/balls_per_direction/1",
                        {"balls_per_direction = 2.5", "not an integer", "an integer >= 0"});
  expect_refused_matrix(R"({"axes": {"edge_balls": [5000000000]}})", "/matrix/axes/edge_balls/0",
                        {"edge_balls = 5000000000", "32-bit"});
}

TEST(StudyErrors, DirectionsNotSixOrFourteen) {
  expect_refused_matrix(R"({"samples": [{"name": "a", "directions": 8}]})",
                        "/matrix/samples/0/directions", {"directions = 8", "6 or 14"});
}

TEST(StudyErrors, UnknownChoice) {
  expect_refused_matrix(R"({"axes": {"mass_mode": ["sum", "exact"]}})", "/matrix/axes/mass_mode/1",
                        {"mass_mode = \"exact\"", "\"sum\", \"paper\" or \"uniform\""});
}

TEST(StudyErrors, UnknownPreset) {
  expect_refused_matrix(R"({"samples": [{"name": "T3", "shape": "table3/sample1"}]})",
                        "/matrix/samples/0/shape",
                        {"shape = \"table3/sample1\"", "\"spheres\" or a clump preset",
                         "table1/sample1", "table2/sample2"});
}

TEST(StudyErrors, ZipListsOfUnequalLength) {
  expect_refused_matrix(
      R"({"zip": [{"p": [0.3, 0.5], "balls_per_direction": [1, 2, 3]}]})",
      "/matrix/zip/0/balls_per_direction",
      {"balls_per_direction has 3 values", "p (/matrix/zip/0/p) has 2", "lists of equal length"});
}

TEST(StudyErrors, EmptyAxisList) {
  expect_refused_matrix(R"({"axes": {"rotation": []}})", "/matrix/axes/rotation",
                        {"rotation = []", "empty", "at least one value"});
}

TEST(StudyErrors, AxisValueNotAList) {
  expect_refused_matrix(R"({"axes": {"rotation": "pfc"}})", "/matrix/axes/rotation",
                        {"rotation = \"pfc\" is not a list"});
}

TEST(StudyErrors, RepeatedAxisValue) {
  expect_refused_matrix(R"({"axes": {"p": [0.5, 0.3, 0.50]}})", "/matrix/axes/p/2",
                        {"0.5", "repeats /matrix/axes/p/0", "distinct values"});
}

TEST(StudyErrors, KeyInTwoPlaces) {
  expect_refused_matrix(
      R"({"axes": {"p": [0.3]}, "samples": [{"name": "a", "shape": "spheres"},
                                           {"name": "b", "p": 0.5}]})",
      "/matrix/axes/p",  // samples are read first: they are the outermost factor
      {"\"p\" is also given at /matrix/samples/1/p", "only one of axes, one zip group or samples"});
  expect_refused_matrix(R"({"zip": [{"p": [0.3]}, {"p": [0.5]}]})", "/matrix/zip/1/p",
                        {"also given at /matrix/zip/0/p"});
}

TEST(StudyErrors, PAndNInOneRun) {
  expect_refused_matrix(
      R"({"axes": {"p": [0.5]}, "samples": [{"name": "a", "n": 3}]})", "/matrix/samples/0/n",
      {"n = 3.0 and p = 0.5 are both given", "run 'a-p=0.5-r1'", "p or n in one run"});
}

TEST(StudyErrors, NBeyondDirections) {
  expect_refused_matrix(
      R"({"axes": {"n": [3, 10]}, "samples": [{"name": "six", "shape": "table2/sample1"}]})",
      "/matrix/axes/n/1",
      {"n = 10.0 exceeds directions = 6", "run 'six-n=10.0-r1'", "[0, directions]"});
}

TEST(StudyErrors, ClumpParameterWithSpheres) {
  // A sample of spheres with a clump parameter of its own.
  expect_refused_matrix(R"({"samples": [{"name": "s", "shape": "spheres", "d3": 0.3}]})",
                        "/matrix/samples/0/d3",
                        {"d3 = 0.3 does not apply to shape \"spheres\"", "run 's-r1'"});
  // A zip group that mixes a clump parameter with a numerical one cannot be skipped
  // for spheres as a whole (docs/STUDY.md, "Spheres").
  expect_refused_matrix(R"({"zip": [{"adjacency": ["hull"], "dt_safety": [0.5]}],
                            "samples": [{"name": "s", "shape": "spheres"}]})",
                        "/matrix/zip/0/adjacency/0",
                        {"adjacency = \"hull\" does not apply to shape \"spheres\"",
                         "run 's-adjacency=hull-dt_safety=0.5-r1'"});
}

TEST(StudyErrors, ReplicatesAndSeedsTogether) {
  expect_refused_matrix(R"({"replicates": 2, "seeds": [1, 2]})", "/matrix/seeds",
                        {"both replicates and seeds", "one of replicates or seeds"});
}

TEST(StudyErrors, BadReplicateCountOrSeeds) {
  expect_refused_matrix(R"({"common_seeds": 1})", "/matrix/common_seeds",
                        {"common_seeds = 1", "true or false"});
  expect_refused_matrix(R"({"replicates": 0})", "/matrix/replicates",
                        {"replicates = 0", "an integer in [1, 100000]"});
  expect_refused_matrix(R"({"seeds": [1, -2]})", "/matrix/seeds/1",
                        {"seed = -2", "[0, 2147483647]"});
  expect_refused_matrix(R"({"seeds": [3, 3]})", "/matrix/seeds/1",
                        {"seed = 3 repeats /matrix/seeds/0", "distinct"});
}

TEST(StudyErrors, SampleNames) {
  expect_refused_matrix(R"({"samples": [{"shape": "spheres"}]})", "/matrix/samples/0/name",
                        {"missing key \"name\""});
  expect_refused_matrix(R"({"samples": [{"name": "T2/S1"}]})", "/matrix/samples/0/name",
                        {"\"T2/S1\"", "letters, digits"});
  expect_refused_matrix(R"({"samples": [{"name": "a", "shape": "spheres"},
                                       {"name": "a", "shape": "table2/sample1"}]})",
                        "/matrix/samples/1/name",
                        {"\"a\" repeats /matrix/samples/0/name", "a different name"});
}

TEST(StudyErrors, SamplesThatGiveTheSameRuns) {
  expect_refused_matrix(R"({"samples": [{"name": "a", "shape": "spheres"},
                                       {"name": "b", "shape": "spheres"}]})",
                        "/matrix/samples", {"runs 'a-r1' and 'b-r1'", "same parameters"});
}

TEST(StudyErrors, TooManyRuns) {
  std::string list = "[";
  for (int i = 1; i <= 100; ++i) list += std::to_string(i) + (i < 100 ? "," : "]");
  expect_refused_matrix(
      R"({"axes": {"cycles": )" + list + R"(, "edge_balls": )" + list + R"(}, "replicates": 11})",
      "/matrix", {"more than 100000 runs", "100 x 100 x 11 replicates"});
}

TEST(StudyErrors, DuplicateJsonKey) {
  // A JSON reader would keep only the second "p" and silently drop an axis.
  expect_refused_matrix(R"({"axes": {"p": [0.3], "p": [0.5]}})", "/matrix/axes/p",
                        {"duplicate key", "each key once per object"});
  expect_refused_matrix(R"({"samples": [{"name": "a"}, {"name": "b", "c": 0.1, "c": 0.2}]})",
                        "/matrix/samples/1/c", {"duplicate key"});
}

TEST(StudyErrors, NotJsonOrNoFile) {
  EXPECT_THROW(parse_study_json("{\"name\": ", "bad.json"), StudyError);
  try {
    load_study_file("/nonexistent/study.json");
    ADD_FAILURE() << "no error";
  } catch (const StudyError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/study.json"), std::string::npos);
  }
}

}  // namespace
}  // namespace ballast
