#include "study/study_scene.hpp"

#include <algorithm>

#include "study/study_keys.hpp"
#include "study/study_run.hpp"

namespace ballast {
namespace {

using nlohmann::json;

// Where each study key goes in a scene file. A key added to kStudyKeys needs a row
// here (StudyScene.EveryStudyKeyHasASceneKey fails otherwise).
constexpr SceneKey kSceneKeys[] = {
    {"shape", "/particles/shape"},
    {"directions", "/particles/clump/directions"},
    {"p", "/particles/clump/p"},
    {"n", "/particles/clump/p"},  // as p = n / directions (resolve_run_clump)
    {"balls_per_direction", "/particles/clump/balls_per_direction"},
    {"c", "/particles/clump/c"},
    {"d3", "/particles/clump/d3"},
    {"edge_balls", "/particles/clump/edge_balls"},
    {"virtual_sphere_factor", "/particles/clump/virtual_sphere_factor"},
    {"adjacency", "/particles/clump/adjacency"},
    {"dt_safety", "/numerics/dt_safety"},
    {"dt", "/numerics/dt"},
    {"rotation", "/numerics/rotation"},
    {"mass_mode", "/particles/mass_mode"},
    {"local_damping", "/numerics/local_damping"},
    {"contact_law", "/materials/contact_law"},
    {"count", "/particles/count"},
    {"levelling_pressure", "/preparation/levelling_pressure"},
    {"gravity_factor", "/preparation/gravity_factor"},
    {"cycles", "/sleeper/cycles"},
};

// The preset a run's clump starts from when it gives clump parameters but no shape:
// docs/STUDY.md says ClumpParams' defaults, which are Table 2 Sample 1's numbers
// (StudyScene.DefaultClumpShapeIsClumpParamsDefaults pins that).
constexpr const char* kDefaultClumpShape = "table2/sample1";

const SceneKey& scene_key(const std::string& study_key) {
  for (const SceneKey& k : kSceneKeys) {
    if (k.study_key == study_key) return k;
  }
  // expand_study admits only registered keys, and every one has a row (tested).
  throw std::logic_error("study key '" + study_key + "' has no scene key");
}

bool brings_clump(const json& params) {
  for (const auto& [key, value] : params.items()) {
    const StudyKey* k = find_study_key(key);
    if (k && (k->group == "clump" || k->group == "shape")) return true;
  }
  return false;
}

}  // namespace

std::span<const SceneKey> scene_keys() {
  return kSceneKeys;
}

json run_scene_json(const json& base_scene, const RunSpec& run) {
  json scene = base_scene;
  if (brings_clump(run.params)) {
    json& particles = scene["particles"];
    particles.erase("clump");
    particles["shape"] = run.params.value("shape", std::string(kDefaultClumpShape));
  }
  for (const auto& [key, value] : run.params.items()) {
    json v = value;
    if (key == "n") v = resolve_run_clump(run.params)->params.p;
    scene[json::json_pointer(std::string(scene_key(key).scene_pointer))] = v;
  }
  scene["particles"]["seed"] = run.seed;
  return scene;
}

BoxTestScene parse_run_scene(const json& run_scene, const RunSpec& run, const std::string& origin,
                             const std::string& scene_path) {
  try {
    return parse_box_test_scene(run_scene);
  } catch (const StudyError&) {
    throw;
  } catch (const SetupError& e) {
    throw StudyError(origin, "",
                     "run '" + run.id + "' (parameters " + run.params.dump() + "): scene '" +
                         scene_path + "' with the run's parameters: " + e.what(),
                     "");
  }
}

}  // namespace ballast
