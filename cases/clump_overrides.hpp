// A JSON object's clump parameters read into a ClumpParams through the parameter
// table (engine/clump_param_table.hpp) and JsonFields: the one route by which a
// preset file sets a clump and a scene's /particles/clump and a study run's
// parameters change it.
#pragma once

#include <nlohmann/json_fwd.hpp>
#include <string>

#include "cases/json_fields.hpp"
#include "engine/clump_generator.hpp"

namespace ballast {

// Reads every overridable parameter `fields` holds into q, each checked against the
// table's range (SetupError naming the key, the value and what is allowed). Other
// keys are left for the caller (JsonFields::finish refuses them in a scene).
void read_clump_overrides(JsonFields& fields, ClumpParams& q);
// The same for every parameter of the table, overridable or not: a preset file.
void read_clump_params(JsonFields& fields, ClumpParams& q);

// The same for a flat object of parameters that may hold other keys too (a study
// run's `params`): only the table's overridable keys are read.
void apply_clump_overrides(const nlohmann::json& params, const std::string& path, ClumpParams& q);

}  // namespace ballast
