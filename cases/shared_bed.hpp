// What a box test's prepared bed depends on: its scene without the fields that only
// the loading reads. Two runs whose scenes give the same text (the seed is in the
// scene) prepare the same bed bit for bit, so a study lets one of them prepare it and
// the others start from it (docs/STUDY.md, "Shared beds"). The bed is the state at
// PrepStage::kPrepared: the plate lifted and the bed settled again, before the sleeper.
#pragma once

#include <nlohmann/json_fwd.hpp>
#include <span>
#include <string>

namespace ballast {

// The scene fields read only from stage 4 on (cases/box_test_load.cpp): the sleeper's
// height, edge radius, speed limit, load and cycles, every measurement, and the local
// damping of the seating. The sleeper's length, preload and gain are not among them:
// the levelling plate uses the gain, and its pressure defaults to the preload over the
// sleeper's footprint.
std::span<const char* const> loading_only_fields();

// The scene without loading_only_fields(), as compact JSON with sorted keys.
std::string bed_defining_text(const nlohmann::json& scene);

}  // namespace ballast
