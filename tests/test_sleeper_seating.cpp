// The two seating settings that docs/TRIALS.md tries (cases/box_test_scene.hpp):
// /sleeper/edge_radius, a sleeper with rounded long edges, and
// /preparation/seating_local_damping, the local damping while the sleeper seats under
// the preload. Each loads one prepared tiny bed (40 spheres) and compares the end
// state's bits: a setting at its neutral value changes nothing, another value changes
// the run, and the cycle after the seating runs with the scene's own local damping.
// The rounded box's geometry is tested in test_walls.cpp.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "cases/box_test_load.hpp"
#include "cases/box_test_prepare.hpp"
#include "engine/state_hash.hpp"
#include "tiny_scene.hpp"

using namespace ballast;
using nlohmann::json;
using test_support::tiny_scene;

namespace {

// The bed is prepared once: neither setting is read before the sleeper comes
// (test_shared_bed.cpp checks that).
const PreparedBed& tiny_bed() {
  static const PreparedBed bed = prepare_box_test(parse_box_test_scene(tiny_scene()), nullptr);
  return bed;
}

struct Loaded {
  std::uint64_t hash;
  double local_damping_after;  // the engine's setting once the cycle has run
  BoxTestResult result;
};

Loaded load_with(const char* pointer, const json& value) {
  json j = tiny_scene();
  if (pointer) j[json::json_pointer(pointer)] = value;
  Simulation sim = tiny_bed().sim;
  Loaded out;
  load_box_test(parse_box_test_scene(j), sim, out.result, nullptr);
  out.hash = state_hash(sim);
  out.local_damping_after = sim.settings().local_damping;
  return out;
}

// The scene as it stands, loaded once for both tests.
const Loaded& plain_run() {
  static const Loaded plain = load_with(nullptr, nullptr);
  return plain;
}

}  // namespace

TEST(SleeperSeating, SeatingDampingActsOnTheSeatingAndTheCycleKeepsTheScenes) {
  const Loaded& plain = plain_run();
  const double scene_alpha = parse_box_test_scene(tiny_scene()).sim.local_damping;
  ASSERT_GT(scene_alpha, 0.0);
  // The scene's own value given explicitly: the same run to the bit.
  EXPECT_EQ(load_with("/preparation/seating_local_damping", scene_alpha).hash, plain.hash);
  // Undamped seating: another run, whose cycle is damped as the scene says.
  const Loaded free = load_with("/preparation/seating_local_damping", 0.0);
  EXPECT_NE(free.hash, plain.hash);
  EXPECT_EQ(free.local_damping_after, scene_alpha);
  EXPECT_EQ(plain.local_damping_after, scene_alpha);
}

TEST(SleeperSeating, ARoundedSleeperChangesTheRunAndASharpOneDoesNot) {
  const Loaded& plain = plain_run();
  EXPECT_EQ(load_with("/sleeper/edge_radius", 0.0).hash, plain.hash);
  // 15 mm of a 40 mm high sleeper: the top spheres under its ends meet a surface
  // that curves away from them, so the run differs.
  const Loaded rounded = load_with("/sleeper/edge_radius", 0.015);
  EXPECT_NE(rounded.hash, plain.hash);
  // The rounded sleeper still goes down into the bed as the load rises to its peak.
  EXPECT_GT(rounded.result.settlement_peak, 0.0);
}
