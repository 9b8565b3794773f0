// The SIMD sphere kernel (engine/sphere_kernel.hpp) evaluates four or eight contacts
// at a time with the scalar contact law's operations in the scalar order, so a run
// must end in the very state the scalar pass reaches: one state hash for every
// kernel width this CPU runs. The scenes make the kernel go through all of its
// paths: contacts that open and close, slide (the Coulomb cap) and roll (the shear
// force turned into the new contact plane), walls, neighbour rebuilds, remade live
// lists, one or two ball materials, with or without friction.
#include <gtest/gtest.h>

#include <utility>
#include <vector>

#include "cases/bed.hpp"
#include "cases/box_test.hpp"
#include "cases/sphere_packing.hpp"
#include "engine/errors.hpp"
#include "engine/sphere_kernel.hpp"
#include "engine/state_hash.hpp"
#include "test_helpers.hpp"

using namespace ballast;

namespace {

// The kernel widths this CPU runs, after the scalar pass (0).
std::vector<int> widths() {
  std::vector<int> w{0};
  for (int lanes : {4, 8})
    if (sphere_kernel_supported(lanes)) w.push_back(lanes);
  return w;
}

struct Outcome {
  std::uint64_t hash;
  int lanes_used;
  long contacts, builds;
  double slip;  // J, friction dissipated: the Coulomb cap was reached
};

Outcome finish(Simulation& sim, double until) {
  while (sim.time() < until) sim.step();
  return {state_hash(sim), sim.sphere_kernel_lanes(), sim.contacts().ball_contacts,
          sim.neighbour_builds(), sim.energy().friction_dissipated};
}

// A cloud of 400 spheres landing at 100 g in a narrow box: a bed within 0.05 s.
Outcome landing_bed(int lanes, double friction) {
  BedOptions o;
  o.sim.simd_lanes = lanes;
  o.count = 400;
  o.length = 0.35;
  o.friction = friction;
  o.sim.damping_ratio = 0.0;  // the kernel's scenes: no dashpots
  o.sim.local_damping = 0.2;
  o.sim.gravity = Vec3(0, 0, -981.0);
  Simulation sim = make_bed(o);
  return finish(sim, 0.05);
}

// The same kind of cloud in a narrower box, with every other sphere of a second
// material: softer and rougher, so that each contact's pair properties come from
// the table. 203 spheres from `floor` (m) up, walls listed by add_walls.
const Vec3 kCloudHi(0.3, 0.15, 1.0);
const double kCloudRadius = 0.5 * box_test::kSphereDiameter;
const Material kHard{1e8, 1e8, 0.3}, kSoft{4e7, 2e7, 0.6};

template <class AddWalls>
Simulation two_material_cloud(int lanes, double floor, AddWalls add_walls) {
  SimulationSettings s;
  s.domain_lo = -Vec3::Constant(2 * kCloudRadius);
  s.domain_hi = kCloudHi + Vec3::Constant(2 * kCloudRadius);
  s.gravity = Vec3(0, 0, -981.0);
  s.local_damping = 0.2;
  s.simd_lanes = lanes;
  Simulation sim(s);
  const Index m0 = sim.add_material(kHard), m1 = sim.add_material(kSoft);
  add_walls(sim);
  const std::vector<Vec3> centres =
      random_loose_packing(203, kCloudRadius, Vec3(0, 0, floor), kCloudHi, 0.3, 7);
  for (std::size_t k = 0; k < centres.size(); ++k)
    sim.add_sphere(centres[k], kCloudRadius, box_test::kDensity, k % 2 == 0 ? m0 : m1);
  return sim;
}

Outcome two_material_bed(int lanes) {
  Simulation sim = two_material_cloud(lanes, 0.0, [](Simulation& sim) {
    for (const Wall& w : box_container(Vec3::Zero(), kCloudHi, kHard, kSoft, /*open_top=*/true))
      sim.add_wall(w);
  });
  return finish(sim, 0.04);
}

// The two-material cloud landing on a solid block (a Box wall, which the kernel
// leaves to the scalar pass) while one end wall moves in and the base slides in its
// own plane. The block is listed before the container (box_first: the scalar pass
// takes every wall contact) or after it (the kernel takes the planes' contacts, the
// scalar pass the block's after them). The block's and the moving wall's total
// forces (N) say that both were touched.
struct WalledOutcome {
  Outcome outcome;
  double block_force, moving_force;
};
WalledOutcome walled_bed(int lanes, bool box_first) {
  Wall block;
  block.name = "block";
  block.shape = WallShape::Box;
  block.lo = Vec3(0.1, -0.1, -0.1);
  block.hi = Vec3(0.2, 0.25, 0.06);
  block.material = kSoft;
  Index block_index = -1, moving = -1;
  // The cloud starts above the block.
  Simulation sim = two_material_cloud(lanes, 0.08, [&](Simulation& sim) {
    if (box_first) block_index = sim.add_wall(block);
    for (Wall w : box_container(Vec3::Zero(), kCloudHi, kHard, kSoft, /*open_top=*/true)) {
      if (w.name == "xmax" || w.name == "base") w.motion = WallMotion::Prescribed;
      if (w.name == "xmax") w.velocity = Vec3(-0.5, 0.0, 0.0);  // m/s: 20 mm in the run
      if (w.name == "base") w.velocity = Vec3(0.3, 0.1, 0.0);   // sliding in its own plane
      const Index index = sim.add_wall(w);
      if (w.name == "xmax") moving = index;
    }
    if (!box_first) block_index = sim.add_wall(block);
  });
  const Outcome out = finish(sim, 0.04);
  return {out, sim.wall_force(block_index).norm(), sim.wall_force(moving).norm()};
}

}  // namespace

TEST(SphereKernel, EveryWidthGivesTheScalarBits) {
  const std::vector<int> w = widths();
  if (w.size() == 1) GTEST_SKIP() << "this CPU has neither AVX2 nor AVX-512";
  const Outcome scalar = landing_bed(0, 0.4);
  EXPECT_EQ(scalar.lanes_used, 0);
  EXPECT_GT(scalar.contacts, 300);  // the bed has formed
  EXPECT_GT(scalar.builds, 10);     // across many neighbour rebuilds
  EXPECT_GT(scalar.slip, 0.0);      // contacts slid
  for (std::size_t k = 1; k < w.size(); ++k) {
    const Outcome simd = landing_bed(w[k], 0.4);
    EXPECT_EQ(simd.lanes_used, w[k]);
    EXPECT_EQ(simd.hash, scalar.hash) << w[k] << " lanes";
  }
}

TEST(SphereKernel, FrictionlessSceneGivesTheScalarBits) {
  const std::vector<int> w = widths();
  if (w.size() == 1) GTEST_SKIP() << "this CPU has neither AVX2 nor AVX-512";
  const Outcome scalar = landing_bed(0, 0.0);
  EXPECT_GT(scalar.contacts, 300);
  EXPECT_EQ(scalar.slip, 0.0);
  for (std::size_t k = 1; k < w.size(); ++k)
    EXPECT_EQ(landing_bed(w[k], 0.0).hash, scalar.hash) << w[k] << " lanes";
}

TEST(SphereKernel, TwoMaterialsGiveTheScalarBits) {
  const std::vector<int> w = widths();
  if (w.size() == 1) GTEST_SKIP() << "this CPU has neither AVX2 nor AVX-512";
  const Outcome scalar = two_material_bed(0);
  EXPECT_GT(scalar.contacts, 150);
  EXPECT_GT(scalar.slip, 0.0);
  for (std::size_t k = 1; k < w.size(); ++k)
    EXPECT_EQ(two_material_bed(w[k]).hash, scalar.hash) << w[k] << " lanes";
}

TEST(SphereKernel, PlanesBesideABoxGiveTheScalarBits) {
  const std::vector<int> w = widths();
  if (w.size() == 1) GTEST_SKIP() << "this CPU has neither AVX2 nor AVX-512";
  for (bool box_first : {false, true}) {
    const WalledOutcome scalar = walled_bed(0, box_first);
    EXPECT_GT(scalar.outcome.contacts, 150);
    EXPECT_GT(scalar.outcome.slip, 0.0);
    EXPECT_GT(scalar.block_force, 1.0) << "the spheres rest on the block";
    EXPECT_GT(scalar.moving_force, 1.0) << "the moving wall pushes on the bed";
    for (std::size_t k = 1; k < w.size(); ++k)
      EXPECT_EQ(walled_bed(w[k], box_first).outcome.hash, scalar.outcome.hash)
          << w[k] << " lanes, box first " << box_first;
  }
}

// One sphere sliding on a frictional floor: no ball–ball candidate at all, so the
// ball–ball lanes have no shear array, yet the wall lanes must apply friction.
TEST(SphereKernel, ALoneSphereSlidesOnAPlaneAsTheScalarPassHasIt) {
  const std::vector<int> w = widths();
  if (w.size() == 1) GTEST_SKIP() << "this CPU has neither AVX2 nor AVX-512";
  const auto slide = [](int lanes) {
    SimulationSettings s = scenes::bare_settings(0.5);
    s.gravity = Vec3(0, 0, -9.81);
    s.simd_lanes = lanes;
    Simulation sim(s);
    const Material m{2e7, 2e7, 0.3};
    const Index mat = sim.add_material(m);
    sim.add_wall(scenes::plane_wall(Vec3::Zero(), Vec3::UnitZ(), m));
    const Index b = sim.add_sphere(Vec3(-0.4, 0, 0.0199), 0.02, 2600.0, mat);
    sim.set_body_velocity(b, Vec3(1.0, 0, 0));
    sim.run(20000);
    return std::make_pair(state_hash(sim), sim.bodies().angular_velocity[b].y());
  };
  const auto scalar = slide(0);
  EXPECT_GT(scalar.second, 1.0) << "friction spins the sphere up (rad/s)";
  for (std::size_t k = 1; k < w.size(); ++k)
    EXPECT_EQ(slide(w[k]).first, scalar.first) << w[k] << " lanes";
}

// A kernel the CPU does not run is refused at set-up, naming the field.
TEST(SphereKernel, UnsupportedWidthIsRefused) {
  for (int lanes : {3, 16}) {
    BedOptions o;
    o.count = 10;
    o.sim.simd_lanes = lanes;
    Simulation sim = make_bed(o);
    test_support::expect_error([&] { sim.step(); }, {"simd_lanes"});
  }
}
