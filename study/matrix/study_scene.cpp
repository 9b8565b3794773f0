#include "study/matrix/study_scene.hpp"

#include <algorithm>
#include <string>
#include <vector>

#include "engine/clump_param_table.hpp"
#include "study/matrix/run_identity.hpp"
#include "study/matrix/study_keys.hpp"

namespace ballast {
namespace {

using nlohmann::json;

// Where each study key goes in a scene file: a clump parameter under
// /particles/clump, the others below. A key added to the study keys needs a row
// (StudyScene.EveryStudyKeyHasASceneKey fails otherwise).
constexpr SceneKey kOtherSceneKeys[] = {
    {"shape", "/particles/shape"},
    {"n", "/particles/clump/p"},  // as p = n / directions (resolve_run_clump)
    {"dt_safety", "/numerics/dt_safety"},
    {"dt", "/numerics/dt"},
    {"rotation", "/numerics/rotation"},
    {"mass_mode", "/particles/mass_mode"},
    {"local_damping", "/numerics/local_damping"},
    {"preset", "/numerics/preset"},
    {"max_stage_steps", "/preparation/max_stage_steps"},
    {"mass_scale", "/numerics/mass_scale"},
    {"ball_stiffness", "/materials/ball_stiffness"},
    {"wall_stiffness", "/materials/wall_stiffness"},
    {"density", "/materials/density"},
    {"box_length", "/box/length"},
    {"contact_law", "/materials/contact_law"},
    {"count", "/particles/count"},
    {"levelling_pressure", "/preparation/levelling_pressure"},
    {"gravity_factor", "/preparation/gravity_factor"},
    {"preload", "/sleeper/preload"},
    {"cycles", "/sleeper/cycles"},
    {"frequency", "/sleeper/frequency"},
};

// Every study key's row, in the study keys' order.
const std::vector<SceneKey>& all_scene_keys() {
  static const std::vector<std::string> clump_pointers = [] {
    std::vector<std::string> p;
    for (const ClumpParamField& f : clump_param_fields())
      p.push_back("/particles/clump/" + std::string(f.name));
    return p;
  }();
  static const std::vector<SceneKey> keys = [] {
    std::vector<SceneKey> k;
    for (const StudyKey& key : study_keys()) {
      for (const SceneKey& other : kOtherSceneKeys)
        if (other.study_key == key.name) k.push_back(other);
      const auto fields = clump_param_fields();
      for (std::size_t i = 0; i < fields.size(); ++i)
        if (fields[i].overridable && fields[i].name == key.name)
          k.push_back({fields[i].name, clump_pointers[i]});
    }
    return k;
  }();
  return keys;
}

// The preset a run's clump starts from when it gives clump parameters but no shape:
// docs/STUDY.md says ClumpParams' defaults, which are Table 2 Sample 1's numbers
// (StudyScene.DefaultClumpShapeIsClumpParamsDefaults pins that).
constexpr const char* kDefaultClumpShape = "table2/sample1";

const SceneKey& scene_key(const std::string& study_key) {
  for (const SceneKey& k : all_scene_keys()) {
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
  return all_scene_keys();
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
