#include "cases/shared_bed.hpp"

#include <nlohmann/json.hpp>

namespace ballast {
namespace {

constexpr const char* kLoadingOnly[] = {
    "/sleeper/height",    "/sleeper/edge_radius",
    "/sleeper/max_speed", "/sleeper/peak_load",
    "/sleeper/frequency", "/sleeper/cycles",
    "/measurement",       "/preparation/seating_local_damping",
};

}  // namespace

std::span<const char* const> loading_only_fields() {
  return kLoadingOnly;
}

std::string bed_defining_text(const nlohmann::json& scene) {
  nlohmann::json kept = scene;
  for (const char* field : kLoadingOnly) {
    const nlohmann::json::json_pointer at{std::string(field)};
    if (!kept.contains(at)) continue;
    kept[at.parent_pointer()].erase(at.back());
  }
  return kept.dump();  // nlohmann's objects keep their keys sorted
}

}  // namespace ballast
