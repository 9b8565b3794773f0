// Shared beds (cases/shared_bed.hpp): a study lets runs whose scenes differ only in
// their loading fields start from one prepared bed, which is only right if the
// preparation reads none of those fields. So each field is changed in turn and the bed
// at the end of the preparation must keep every bit (state_hash), while a field the
// preparation does read (the preload, which sets the levelling plate's default
// pressure) must change it; and the key must drop exactly the loading fields.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "cases/box_test_prepare.hpp"
#include "cases/box_test_scene.hpp"
#include "cases/shared_bed.hpp"
#include "engine/state_hash.hpp"
#include "tiny_scene.hpp"

using namespace ballast;
using nlohmann::json;
using test_support::tiny_scene;

namespace {

json changed_at(json scene, const char* field, const json& value) {
  scene[json::json_pointer(field)] = value;
  return scene;
}

std::uint64_t prepared_bed_hash(const json& scene) {
  const PreparedBed bed = prepare_box_test(parse_box_test_scene(scene), nullptr);
  return state_hash(bed.sim);
}

// A valid value other than the scene's own for each loading-only field.
const std::pair<const char*, json> kChanged[] = {
    {"/sleeper/height", 0.03},
    {"/sleeper/edge_radius", 0.01},
    {"/preparation/seating_local_damping", 0.9},
    {"/sleeper/max_speed", 0.25},
    {"/sleeper/peak_load", 2500.0},
    {"/sleeper/frequency", 30.0},
    {"/sleeper/cycles", 3},
    {"/measurement/series_every", 7},
    {"/measurement/cube_side", 0.004},
    {"/measurement/zone_depth", 0.03},
    {"/measurement/snapshot_cycles", json::array({1})},
};

}  // namespace

TEST(SharedBed, TheKeyDropsTheLoadingFieldsAndKeepsTheRest) {
  const json scene = tiny_scene();
  const std::string key = bed_defining_text(scene);
  for (const auto& [field, value] : kChanged)
    EXPECT_EQ(bed_defining_text(changed_at(scene, field, value)), key) << field;
  for (const char* field : {"/sleeper/preload", "/sleeper/length", "/sleeper/gain",
                            "/particles/seed", "/preparation/gravity_factor"})
    EXPECT_NE(bed_defining_text(changed_at(scene, field, 0.5)), key) << field;
  // Every loading-only field is one the scene reads: a misspelt pointer would keep
  // nothing out of the key (the measurement section is dropped whole).
  for (const char* field : loading_only_fields()) {
    if (std::string(field) == "/measurement") continue;
    EXPECT_ANY_THROW(parse_box_test_scene(changed_at(scene, field, "not a number"))) << field;
  }
}

TEST(SharedBed, ThePreparationReadsNoLoadingField) {
  const json scene = tiny_scene();
  const std::uint64_t bed = prepared_bed_hash(scene);
  for (const auto& [field, value] : kChanged)
    EXPECT_EQ(prepared_bed_hash(changed_at(scene, field, value)), bed) << field;
  EXPECT_NE(prepared_bed_hash(changed_at(scene, "/sleeper/preload", 400.0)), bed)
      << "the preload sets the plate's pressure";
}
