// Box-test scene files: the paper's numbers are the defaults, the shipped scenes
// parse, clump parameters override a preset, and every bad value is refused with
// its JSON path, the value and what is allowed.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "cases/box_test_scene.hpp"
#include "engine/errors.hpp"
#include "test_helpers.hpp"

using namespace ballast;
using nlohmann::json;

namespace {

std::string error_of(const json& j) {
  return test_support::error_message([&] { parse_box_test_scene(j); });
}

}  // namespace

TEST(BoxTestScene, DefaultsAreThePapers) {
  const BoxTestScene s = parse_box_test_scene(json::object());
  EXPECT_EQ(s.count, 1936);
  EXPECT_DOUBLE_EQ(s.diameter, 0.03625);
  EXPECT_DOUBLE_EQ(s.length, 0.7);
  EXPECT_DOUBLE_EQ(s.width, 0.3);
  EXPECT_DOUBLE_EQ(s.height, 0.45);
  EXPECT_DOUBLE_EQ(s.ball.kn, 5.08e9);
  EXPECT_DOUBLE_EQ(s.ball.ks, 5.08e9);
  EXPECT_DOUBLE_EQ(s.base.kn, 2.54e6);
  EXPECT_DOUBLE_EQ(s.density, 2600.0);
  EXPECT_DOUBLE_EQ(s.friction_compaction, 0.3);
  EXPECT_DOUBLE_EQ(s.friction_loading, 0.5);
  EXPECT_DOUBLE_EQ(s.sim.local_damping, 0.7);
  EXPECT_DOUBLE_EQ(s.preload, 3e3);
  EXPECT_DOUBLE_EQ(s.peak_load, 40e3);
  EXPECT_DOUBLE_EQ(s.frequency, 3.0);
  EXPECT_FALSE(s.clumps.has_value());
}

TEST(BoxTestScene, ShippedScenesParse) {
  const std::string dir = std::string(BALLAST_CASES_DIR) + "/box_test/";
  EXPECT_FALSE(load_box_test_scene(dir + "spheres.json").clumps.has_value());
  const BoxTestScene s1 = load_box_test_scene(dir + "sample1.json");
  ASSERT_TRUE(s1.clumps.has_value());
  EXPECT_DOUBLE_EQ(s1.clumps->virtual_sphere_factor, 1.26);
  const BoxTestScene s2 = load_box_test_scene(dir + "sample2.json");
  ASSERT_TRUE(s2.clumps.has_value());
  EXPECT_EQ(s2.clumps->directions, 14);
  EXPECT_DOUBLE_EQ(s2.clumps->virtual_sphere_factor, 1.31);
  EXPECT_LT(load_box_test_scene(dir + "smoke.json").count, 500);
}

TEST(BoxTestScene, ClumpParametersOverrideThePreset) {
  const json j = {{"particles", {{"shape", "table2/sample1"}, {"clump", {{"p", 0.3}}}}}};
  const BoxTestScene s = parse_box_test_scene(j);
  ASSERT_TRUE(s.clumps.has_value());
  EXPECT_DOUBLE_EQ(s.clumps->p, 0.3);
  EXPECT_EQ(s.clumps->directions, 6);
}

TEST(BoxTestScene, BadInputNamesPathValueAndAllowed) {
  const std::string unknown = error_of({{"sleeper", {{"lenght", 0.2}}}});
  EXPECT_NE(unknown.find("/sleeper/lenght"), std::string::npos) << unknown;
  EXPECT_NE(unknown.find("length"), std::string::npos) << unknown;  // lists the known keys

  const std::string type = error_of({{"numerics", {{"dt_safety", "big"}}}});
  EXPECT_NE(type.find("/numerics/dt_safety"), std::string::npos) << type;
  EXPECT_NE(type.find("\"big\""), std::string::npos) << type;
  EXPECT_NE(type.find("(0, 1]"), std::string::npos) << type;

  const std::string range = error_of({{"sleeper", {{"peak_load", 1000.0}}}});
  EXPECT_NE(range.find("/sleeper/peak_load = 1000"), std::string::npos) << range;
  EXPECT_NE(range.find("> preload"), std::string::npos) << range;

  const std::string edge = error_of({{"sleeper", {{"edge_radius", 0.06}}}});
  EXPECT_NE(edge.find("/sleeper/edge_radius = 0.06"), std::string::npos) << edge;
  EXPECT_NE(edge.find("half the smaller of /sleeper/length and /sleeper/height"), std::string::npos)
      << edge;

  const std::string shape = error_of({{"particles", {{"shape", "table9/sample1"}}}});
  EXPECT_NE(shape.find("table2/sample1"), std::string::npos) << shape;  // lists the presets

  const std::string rotation = error_of({{"numerics", {{"rotation", "euler"}}}});
  EXPECT_NE(rotation.find("\"pfc\" or \"full\""), std::string::npos) << rotation;

  const std::string sphere_clump = error_of({{"particles", {{"clump", {{"p", 0.5}}}}}});
  EXPECT_NE(sphere_clump.find("/particles/clump"), std::string::npos) << sphere_clump;
}

TEST(BoxTestScene, ABedThatCannotFormInItsBoxIsRefusedWhileParsing) {
  // The paper's 1,936 spheres of 36.25 mm, loose at porosity 0.5, hold
  // 1936·π·d³/6 / 0.5 = 0.0966 m³: one diameter deep over at most 2.66 m² of floor,
  // and 1.8 box heights (0.81 m) over the 0.7 × 0.3 m floor at most 3,410 of them.
  EXPECT_EQ(error_of(json::object()), "(accepted)");
  EXPECT_EQ(error_of({{"box", {{"length", 8.8}}}}), "(accepted)");  // 2.64 m²
  const std::string wide = error_of({{"box", {{"length", 8.9}}}});  // 2.67 m²
  EXPECT_NE(wide.find("/box/length x /box/width = 2.67"), std::string::npos) << wide;
  EXPECT_NE(wide.find("at most 2.66"), std::string::npos) << wide;
  EXPECT_EQ(error_of({{"particles", {{"count", 3400}}}}), "(accepted)");
  const std::string many = error_of({{"particles", {{"count", 3420}}}});
  EXPECT_NE(many.find("/particles/count = 3420"), std::string::npos) << many;
  EXPECT_NE(many.find("1.8 box heights"), std::string::npos) << many;
  const std::string big = error_of({{"particles", {{"diameter", 0.31}}}});
  EXPECT_NE(big.find("/particles/diameter = 0.31"), std::string::npos) << big;
  EXPECT_NE(big.find("smallest side, 0.3"), std::string::npos) << big;
  // What a new user tried: a box a kilometre long.
  EXPECT_NE(error_of({{"box", {{"length", 1e6}}}}).find("/box/length x /box/width"),
            std::string::npos);
}

TEST(BoxTestScene, SeedTakesAll64Bits) {
  // A study run's seed is a 64-bit hash (docs/STUDY.md): above INT64_MAX too.
  const json top = json::parse(R"({"particles": {"seed": 18446744073709551615}})");
  EXPECT_EQ(parse_box_test_scene(top).seed, 18446744073709551615ULL);
  const std::string negative = error_of({{"particles", {{"seed", -1}}}});
  EXPECT_NE(negative.find("/particles/seed = -1"), std::string::npos) << negative;
  EXPECT_NE(negative.find("[0, 2^64 - 1]"), std::string::npos) << negative;
  const std::string fraction = error_of({{"particles", {{"seed", 1.5}}}});
  EXPECT_NE(fraction.find("/particles/seed = 1.5"), std::string::npos) << fraction;
}

// numerics/dt fixes the timestep; unset, the run takes dt_safety × the critical estimate.
TEST(BoxTestScene, FixedTimestepIsOptionalAndPositive) {
  EXPECT_FALSE(parse_box_test_scene(json::object()).sim.fixed_dt.has_value());
  const BoxTestScene s = parse_box_test_scene(json::parse(R"({"numerics": {"dt": 1e-6}})"));
  ASSERT_TRUE(s.sim.fixed_dt.has_value());
  EXPECT_DOUBLE_EQ(*s.sim.fixed_dt, 1e-6);
  const std::string e = error_of(json::parse(R"({"numerics": {"dt": -1e-6}})"));
  EXPECT_NE(e.find("/numerics/dt"), std::string::npos) << e;
  EXPECT_NE(e.find("> 0 s"), std::string::npos) << e;
}

// Loading a run could only refuse hours in is refused while parsing
// (cases/scene_bounds.cpp), each bound at its value for the paper's materials.
TEST(BoxTestScene, LoadingBoundsFollowTheBallMaterial) {
  // The whole peak load on one ball-sleeper contact at an overlap of a radius: the
  // paper's kn = 5.08e9 N/m for ball and sleeper in series, 2.54e9 N/m, times
  // 18.125 mm is 4.60e7 N.
  const double carried = 2.54e9 * 0.018125;
  EXPECT_EQ(error_of({{"sleeper", {{"peak_load", 0.99 * carried}}}}), "(accepted)");
  const std::string load = error_of({{"sleeper", {{"peak_load", 1.01 * carried}}}});
  EXPECT_NE(load.find("/sleeper/peak_load"), std::string::npos) << load;
  EXPECT_NE(load.find("at most 4.6e+07 N"), std::string::npos) << load;
  // A cycle of at least 20 steps of 0.8 x the lone sphere's timestep: m = 2600 kg/m3
  // x pi d3/6 = 0.0649 kg, floor kn = ks = 2.54e9 N/m, w2 = 4.5 kn/m.
  const double m = 2600.0 * kPi * std::pow(0.03625, 3) / 6.0;
  const double dt = 0.8 / std::sqrt(4.5 * 2.54e9 / m);
  const double fastest = 1.0 / (20.0 * dt);
  EXPECT_EQ(error_of({{"sleeper", {{"frequency", 0.99 * fastest}}}}), "(accepted)");
  const std::string fast = error_of({{"sleeper", {{"frequency", 1.01 * fastest}}}});
  EXPECT_NE(fast.find("/sleeper/frequency"), std::string::npos) << fast;
  // At most 1e12 steps: at 3 Hz that is 1e12 x 3 x dt cycles.
  const long most = static_cast<long>(1e12 * 3.0 * dt);
  EXPECT_EQ(error_of({{"sleeper", {{"cycles", long(0.99 * most)}}}}), "(accepted)");
  const std::string many = error_of({{"sleeper", {{"cycles", long(1.01 * most)}}}});
  EXPECT_NE(many.find("/sleeper/cycles"), std::string::npos) << many;
  // A density or stiffness that leaves no finite timestep.
  const std::string light = error_of({{"materials", {{"density", 1e-300}}}});
  EXPECT_NE(light.find("/materials/density"), std::string::npos) << light;
  const std::string stiff = error_of({{"materials", {{"ball_stiffness", 1e308}}}});
  EXPECT_NE(stiff.find("ball_stiffness"), std::string::npos) << stiff;
  const std::string speed = error_of({{"sleeper", {{"max_speed", 101.0}}}});
  EXPECT_NE(speed.find("/sleeper/max_speed"), std::string::npos) << speed;
}

TEST(BoxTestScene, MeasurementsFitTheColumnUnderTheSleeper) {
  EXPECT_EQ(error_of({{"measurement", {{"cube_side", 0.25}}}}), "(accepted)");
  const std::string wide = error_of({{"measurement", {{"cube_side", 0.26}}}});
  EXPECT_NE(wide.find("/measurement/cube_side = 0.26"), std::string::npos) << wide;
  // The column: 0.25 x 0.3 m, as deep as 1,936 spheres fill loose, 0.46 m capped by
  // the box's 0.45 m; 1e8 cubes of it are 0.70 mm cubes.
  const double smallest = std::cbrt(0.25 * 0.3 * 0.45 / 1e8);
  EXPECT_EQ(error_of({{"measurement", {{"cube_side", 1.01 * smallest}}}}), "(accepted)");
  const std::string fine = error_of({{"measurement", {{"cube_side", 0.99 * smallest}}}});
  EXPECT_NE(fine.find("at least 0.000696 m"), std::string::npos) << fine;
  const std::string deep = error_of({{"measurement", {{"zone_depth", 0.46}}}});
  EXPECT_NE(deep.find("/measurement/zone_depth"), std::string::npos) << deep;
}
