// A study file expanded into independent runs: validation and expansion only, nothing
// runs here. Format, expansion order, ids, seeds and error messages: docs/STUDY.md.
//
//   {"name": "default", "scene": "box_test/smoke.json", "seed": 2007,
//    "matrix": {"axes": {...}, "zip": [{...}], "samples": [{...}], "replicates": 3}}
//
// Runs are the product of the samples (outermost), the axes in the order written, the
// zip groups in the order written, and the replicates (innermost).
#pragma once

#include <cstddef>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "study/matrix/study_error.hpp"

namespace ballast {

struct RunSpec {
  std::string id;          // stable, readable, unique within the study (run_id())
  std::string sample;      // the sample's name; empty when the study lists no samples
  nlohmann::json params;   // every key that applies to this run, values in canonical form
  std::uint64_t seed = 0;  // run_seed(study seed, params or {} with common_seeds, replicate)
  int replicate = 1;       // the replicate number: 1..N for "replicates": N, or from "seeds"
  std::size_t index = 0;   // position in StudySpec::runs
};

struct StudySpec {
  std::string name;
  std::string scene;       // as written in the file
  std::string scene_path;  // scene resolved against the study file's folder (load_study_file)
  std::uint64_t seed = 0;
  nlohmann::ordered_json source;  // the study file as parsed, keys in the order written
  std::vector<RunSpec> runs;
};

// The most runs one study may expand to; a larger product is almost surely a mistake
// (and would take the memory before it took the cluster).
inline constexpr std::size_t kMaxStudyRuns = 100000;

// Validates the whole study and expands it. `origin` names the JSON in error messages.
// Throws StudyError (path, value, what is allowed) on the first problem found.
StudySpec expand_study(const nlohmann::ordered_json& study, const std::string& origin);
// Same, from a nlohmann::json: its object keys are already sorted, so axes and zip
// groups' keys nest in alphabetical order rather than in the order written.
StudySpec expand_study(const nlohmann::json& study, const std::string& origin);
// Reads, parses (comments allowed, duplicate keys refused) and expands a study file;
// scene_path is the scene relative to the file's folder.
StudySpec load_study_file(const std::string& path);

}  // namespace ballast
