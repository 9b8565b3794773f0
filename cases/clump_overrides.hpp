// A JSON object's clump parameters applied to a ClumpParams through the parameter
// table (engine/clump_param_table.hpp): the one route by which a scene's
// /particles/clump and a study run's parameters change a preset's clump.
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

// The same for a flat object of parameters that may hold other keys too (a study
// run's `params`): only the table's overridable keys are read.
void apply_clump_overrides(const nlohmann::json& params, const std::string& path, ClumpParams& q);

}  // namespace ballast
