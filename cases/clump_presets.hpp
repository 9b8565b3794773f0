// Clump parameter sets from JSON: the presets of Lu & McDowell 2007 Tables 1 and 2
// (cases/presets/table1/sample1.json ... table2/sample2.json) and user files.
//
// A file holds the ClumpParams fields by name (directions, p, balls_per_direction, c,
// d3, edge_balls, virtual_sphere_factor; optional adjacency, nominal_diameter,
// min_radius_fraction), the material density (optional, kg/m³), the paper's own
// counts where it gives them ("paper": {"clumps", "balls"}) and documentation fields
// that are read and ignored: "source", "description", "notes" and any "*_source" or
// "*_note". Any other field is an error, so that a misspelt parameter cannot be
// silently replaced by its default.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "engine/clump_generator.hpp"

namespace ballast {

struct ClumpPreset {
  std::string name;         // "table1/sample2", or the file path for user files
  std::string source;       // where the numbers come from
  std::string description;  // one line
  ClumpParams params;
  double density = 2600.0;  // kg/m³
  // The paper's count of clumps and balls for this sample, when it reports one.
  std::optional<int> paper_clumps, paper_balls;
};

// Directory the named presets are read from: BALLAST_CASES_DIR/presets.
std::string clump_preset_dir();
// Names of the presets there ("table1/sample1", ...), sorted.
std::vector<std::string> available_clump_presets();

// A named preset; an unknown name throws std::invalid_argument listing the names.
ClumpPreset load_clump_preset(const std::string& name);
// A user's JSON file (same format); errors name the file and the field.
ClumpPreset load_clump_params_file(const std::string& path);
// Parses JSON text; `origin` names it in error messages.
ClumpPreset parse_clump_preset(std::string_view json_text, const std::string& origin);

}  // namespace ballast
