// Named numerics presets for a box-test scene: "numerics": {"preset": "fast"}.
//
// A preset is a list of scene fields with values, chosen from the measured trade
// between speed and accuracy on the box test (docs/TRADEOFFS.md, made by
// scripts/tradeoff_table.py from cases/tradeoff_study.json). It fills the fields the
// scene leaves out, before the scene is read, so that a field the scene gives itself
// always wins and the archive's scene plus the preset's name say every value a run used.
// The presets touch numerics only (timestep, step limits, mass properties and mass
// scaling, contact stiffness); the test itself (box, sleeper, loads, frequency) stays
// the scene's.
#pragma once

#include <nlohmann/json_fwd.hpp>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace ballast {

struct PresetField {
  std::string_view pointer;  // JSON Pointer into the scene, e.g. "/numerics/dt_safety"
  std::string_view value;    // the value as JSON text: "0.8", "\"pfc\""
};

struct NumericsPreset {
  std::string_view name;
  std::span<const PresetField> fields;
};

std::span<const NumericsPreset> numerics_presets();
// "\"paper\", \"balanced\" or \"fast\"", for messages and help.
std::string numerics_preset_names();

// Fills `scene` from the preset named at /numerics/preset, if any: each preset field
// the scene does not give is set. Returns the preset's fields the scene gave itself
// (kept, over the preset's values), for the run's log. Throws SetupError naming
// /numerics/preset, its value and the allowed names when the name is unknown or not a
// string.
std::vector<std::string> apply_numerics_preset(nlohmann::json& scene);

}  // namespace ballast
