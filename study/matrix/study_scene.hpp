// The scene one run of a study runs: the base scene file's JSON with the run's
// parameters written onto scene keys (docs/STUDY.md, "Running a study"), then read by
// parse_box_test_scene so that the scene's own validation applies to every run.
//
// Clump keys go to /particles/clump/<key>; one table (kOtherSceneKeys in
// study_scene.cpp) says where each other study key goes:
//
//   shape             -> /particles/shape        dt_safety     -> /numerics/dt_safety
//   directions, p, .. -> /particles/clump/<key>  rotation      -> /numerics/rotation
//   n                 -> /particles/clump/p      mass_mode     -> /particles/mass_mode
//                        as p = n / directions   local_damping -> /numerics/local_damping
//   gravity_factor    -> /preparation/gravity_factor
//   cycles            -> /sleeper/cycles         the run's seed -> /particles/seed
#pragma once

#include <nlohmann/json.hpp>
#include <span>
#include <string>
#include <string_view>

#include "cases/box_test_scene.hpp"
#include "study/matrix/study_matrix.hpp"

namespace ballast {

struct SceneKey {
  std::string_view study_key;      // a study key (study_keys.hpp)
  std::string_view scene_pointer;  // JSON Pointer into a scene file (docs/BOX_TEST.md)
};

// Every study key and where it goes, in the order of study_keys().
std::span<const SceneKey> scene_keys();

// The base scene with the run's parameters and seed written in. A run that names a
// shape or gives any clump parameter brings its whole clump: the base scene's
// /particles/clump is dropped, the shape is the run's (or table2/sample1, whose
// numbers are ClumpParams' defaults, when the run gives clump parameters without a
// shape), so that the run's clump is exactly resolve_run_clump(params). Otherwise the
// base scene's particles stay as they are.
nlohmann::json run_scene_json(const nlohmann::json& base_scene, const RunSpec& run);

// parse_box_test_scene of a run's scene (run_scene_json). A scene the run's parameters
// make invalid is a StudyError naming the study file (origin), the run and its
// parameters, and the scene's message (JSON path in the scene, value, what is allowed).
BoxTestScene parse_run_scene(const nlohmann::json& run_scene, const RunSpec& run,
                             const std::string& origin, const std::string& scene_path);

}  // namespace ballast
