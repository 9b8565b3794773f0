// Packings into a simulation and back (cases/packing_bodies.hpp), box-test scenes
// whose sample comes from a packing file, and the peer benchmark's scene
// (cases/bench_bed.hpp) on beds whose answer is known in closed form.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "cases/bench_bed.hpp"
#include "cases/box_test_load.hpp"
#include "cases/packing_bodies.hpp"
#include "engine/errors.hpp"
#include "test_helpers.hpp"

using namespace ballast;

using ballast::test_support::expect_error;

namespace {

constexpr double kRho = 2600.0, kG = 9.81;

double ball_mass(double r) {
  return scenes::sphere_mass(r, kRho);
}

// A clump of three overlapping balls, a sphere, and a two-ball clump.
Packing mixed_packing() {
  Packing p;
  p.clumps = true;
  p.add_body(4, {Vec3(0.10, 0.10, 0.05), Vec3(0.115, 0.10, 0.05), Vec3(0.10, 0.112, 0.058)},
             {0.012, 0.008, 0.006});
  p.add_body(9, {Vec3(0.20, 0.15, 0.03)}, {0.018125});
  p.add_body(2, {Vec3(0.30, 0.10, 0.04), Vec3(0.30, 0.10, 0.055)}, {0.01, 0.007});
  return p;
}

SimulationSettings roomy() {
  SimulationSettings s;
  s.domain_lo = Vec3::Constant(-1.0);
  s.domain_hi = Vec3::Constant(2.0);
  return s;
}

std::string write_temp(const std::string& name, const std::string& text) {
  const std::string path = ::testing::TempDir() + "/" + name;
  std::ofstream(path) << text;
  return path;
}

}  // namespace

TEST(PackingImport, ClumpsGetSummedMassAndTheirBallsLandWhereTheFilePutThem) {
  const Packing p = mixed_packing();
  Simulation sim(roomy());
  const Index mat = sim.add_material({1e9, 1e9, 0.3});
  add_packing(sim, p, {{MassMode::kSum, kRho, 0.005}, 0.03625}, mat);
  ASSERT_EQ(sim.bodies().size(), 3);
  ASSERT_EQ(sim.balls().size(), p.balls());
  EXPECT_FALSE(sim.bodies().is_sphere[0]);
  EXPECT_TRUE(sim.bodies().is_sphere[1]);  // a one-ball body is a sphere
  // Mode "sum": the balls' masses added, overlaps counted twice (eq 12).
  EXPECT_NEAR(sim.bodies().mass[0], ball_mass(0.012) + ball_mass(0.008) + ball_mass(0.006), 1e-15);
  EXPECT_NEAR(sim.bodies().mass[1], ball_mass(0.018125), 1e-15);
  // Centre of mass: the mass-weighted mean of the ball centres (eq 13).
  const Vec3 com =
      (ball_mass(0.01) * Vec3(0.30, 0.10, 0.04) + ball_mass(0.007) * Vec3(0.30, 0.10, 0.055)) /
      (ball_mass(0.01) + ball_mass(0.007));
  EXPECT_LT((sim.bodies().position[2] - com).norm(), 1e-15);
  // Balls back at the file's positions to rounding (offsets in the principal frame
  // turned back by the principal axes): far below the 1e-9 m overlaps that matter.
  for (Index k = 0; k < p.balls(); ++k) {
    EXPECT_LT((sim.balls().position[k] - p.centre[k]).norm(), 1e-16) << "ball " << k;
    EXPECT_EQ(sim.balls().radius[k], p.radius[k]);
  }
  // And out again: the same bodies, positions to rounding.
  const Packing q = packing_of(sim);
  EXPECT_TRUE(q.clumps);
  EXPECT_EQ(q.body_first, p.body_first);
  for (Index k = 0; k < p.balls(); ++k) EXPECT_LT((q.centre[k] - p.centre[k]).norm(), 1e-16);
}

TEST(PackingImport, SphereBedExportsBitForBit) {
  Packing p;
  for (int k = 0; k < 5; ++k) p.add_body(k, {Vec3(0.1 + 0.04 * k, 0.1 / 3.0, 0.0181)}, {0.018});
  Simulation sim(roomy());
  add_packing(sim, p, {{MassMode::kPaper, kRho, 0.005}, 0.03625}, sim.add_material({1e9, 1e9, 0}));
  const Packing q = packing_of(sim);
  EXPECT_FALSE(q.clumps);
  EXPECT_EQ(q.centre, p.centre);
  EXPECT_EQ(q.radius, p.radius);
}

TEST(PackingImport, ErrorsPointIntoTheFile) {
  Packing p = mixed_packing();
  p.source = "bed.txt";
  p.line = {3, 4, 5, 7, 9, 10};
  SimulationSettings s = roomy();
  s.domain_hi = Vec3::Constant(0.25);  // the last clump lies outside
  Simulation sim(s);
  expect_error(
      [&] {
        add_packing(sim, p, {{MassMode::kSum, kRho, 0.005}, 0.03625},
                    sim.add_material({1e9, 1e9, 0}));
      },
      {"bed.txt:9: invalid ball position"});
}

TEST(PackingImport, SceneRefusesGeneratorKeysBesideAFile) {
  using nlohmann::json;
  for (const char* key : {"count", "seed", "shape"}) {
    json j = {{"particles", {{"file", "bed.txt"}}}};
    j["particles"][key] = std::string(key) == "shape" ? json("spheres") : json(5);
    expect_error(
        [&] { parse_box_test_scene(j); },
        {"invalid /particles/" + std::string(key) + " = ", "together with /particles/file"});
  }
  const json j = {{"particles", {{"file", "bed.txt"}}},
                  {"preparation", {{"expansion_speed", 0.1}}}};
  EXPECT_THROW(parse_box_test_scene(j), SetupError);
  // A relative file is found beside the scene file; mass_mode goes with a file.
  const BoxTestScene s = parse_box_test_scene(
      {{"particles", {{"file", "beds/bed.txt"}, {"mass_mode", "sum"}}}}, "/data/scenes");
  EXPECT_EQ(s.packing_file, "/data/scenes/beds/bed.txt");
  EXPECT_EQ(s.mass_mode, MassMode::kSum);
  EXPECT_FALSE(s.clumps.has_value());
}

TEST(PackingImport, ImportedBedStandsForThePreparedSample) {
  // Three spheres resting side by side on the base. With no settling before
  // compaction, no levelling plate and stop_after "prepare", no step runs: the bed
  // comes back as it went in, through the run's end-of-run hook (`ballast run
  // --export-packing`).
  const std::string bed = write_temp("ballast_import_bed.txt",
                                     "0.05 0.05 0.018 0.018\n0.10 0.05 0.018 0.018\n"
                                     "0.15 0.05 0.018 0.018\n");
  nlohmann::json j = {
      {"particles", {{"file", bed}}},
      {"box", {{"length", 0.2}, {"width", 0.1}, {"height", 0.1}}},
      {"preparation",
       {{"frictionless_settling", false}, {"levelling_pressure", 0.0}, {"stop_after", "prepare"}}}};
  Packing out;
  const BoxTestResult r = run_box_test(parse_box_test_scene(j), nullptr,
                                       [&](const Simulation& sim) { out = packing_of(sim); });
  EXPECT_EQ(r.bodies, 3);
  EXPECT_TRUE(r.stages.empty());
  EXPECT_FALSE(r.loaded);
  EXPECT_EQ(out.centre, read_packing_file(bed).centre);
  // With compaction the stages run as usual on the imported bed (cut short: three
  // spheres side by side never reach the ratio rule's coordination).
  j["preparation"]["stop_after"] = "compact";
  j["preparation"]["max_stage_steps"] = 2000;
  const BoxTestResult c = run_box_test(parse_box_test_scene(j), nullptr);
  ASSERT_EQ(c.stages.size(), 3u);
  EXPECT_EQ(c.stages[0].name, "compact");
  EXPECT_EQ(c.before.stats.wall_contacts, 3);  // each on the base (side walls 32 mm away)
}

// ---- the peer benchmark's scene ----

// Bodies placed exactly at their static overlap under the benchmark physics stay at
// rest: a sphere on the floor (δ = m·g/k), a sphere on a sphere on the floor
// (δ = m·g/k between them, 2m·g/k at the floor) and an upright two-ball clump on its
// lower ball (δ = M·g/k with M summed). With k the per-contact stiffness this holds;
// were the entity stiffness used per contact (no factor 2) or a mass counted another
// way, the bodies would oscillate with energy ~ (δ error)²·k.
TEST(BenchBed, BodiesAtTheirStaticOverlapStayAtRest) {
  const double k = 5.08e9, r = 0.018125, m = ball_mass(r);
  const double r1 = 0.012, r2 = 0.008, m2 = ball_mass(r1) + ball_mass(r2);
  Packing p;
  p.clumps = true;
  p.add_body(0, {Vec3(0.1, 0.15, r - m * kG / k)}, {r});
  const double z1 = r - 2.0 * m * kG / k;
  p.add_body(1, {Vec3(0.3, 0.15, z1)}, {r});
  p.add_body(2, {Vec3(0.3, 0.15, z1 + 2.0 * r - m * kG / k)}, {r});
  const double z = r1 - m2 * kG / k;
  p.add_body(3, {Vec3(0.5, 0.15, z), Vec3(0.5, 0.15, z + 0.015)}, {r1, r2});
  Simulation sim = make_bench_bed(p, BenchBedOptions{});
  sim.run(2000);
  const BenchBedPhysics b = measure_bench_bed(sim);
  EXPECT_EQ(b.ball_ball.count, 1);
  EXPECT_EQ(b.ball_wall.count, 3);
  EXPECT_NEAR(b.ball_ball.normal, m * kG, 1e-6 * m * kG);
  EXPECT_NEAR(b.ball_wall.normal, (m + 2.0 * m + m2) * kG / 3.0, 1e-6 * m * kG);
  EXPECT_LT(b.all.tangential, 1e-9);
  // Rounding of the start positions (~4e-18 m) leaves at most ~k·(4e-18)² of energy.
  EXPECT_LT(b.kinetic(), 1e-20);
  EXPECT_DOUBLE_EQ(sim.dt(), 1e-6);
}

TEST(BenchBed, FallingBallGainsTheKineticEnergyGravityGives) {
  // One sphere 10 mm above the floor, 2,000 steps of 1 µs: free fall for 2 ms.
  Packing p;
  p.add_body(0, {Vec3(0.35, 0.15, 0.05)}, {0.018125});
  Simulation sim = make_bench_bed(p, BenchBedOptions{});
  sim.run(2000);
  const BenchBedPhysics b = measure_bench_bed(sim);
  EXPECT_EQ(b.all.count, 0);
  // Leapfrog from rest: each step kicks the half-step velocity by g·dt, so after n
  // steps it is n·g·dt (to rounding).
  const double v = 2000 * 1e-6 * kG, m = ball_mass(0.018125);
  EXPECT_NEAR(b.kinetic_translational, 0.5 * m * v * v, 1e-12 * m * v * v);
  EXPECT_EQ(b.kinetic_rotational, 0.0);
}
