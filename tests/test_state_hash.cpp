// The state hash (engine/state_hash.hpp) must see every dynamic quantity a run
// reports: a determinism test that compares hashes is only as strict as the hash.
// Each case flips the last bit of one value in a copy of a running scene and
// expects a different hash; the copy left alone must give the same one.
// Mutations that must break it (tests/mutations.tsv): the accumulated rotation, the
// orientations, the per-body damping ledger or the shear history left out of
// state_hash; each failed the flip of that quantity.
#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "engine/state_hash.hpp"
#include "test_helpers.hpp"

using namespace ballast;

namespace {

// The stores are reachable only read-only; the copies below are not const objects,
// so writing through them is defined. Only this test writes there.
template <class T>
T& writable(const T& x) {
  return const_cast<T&>(x);
}

// The last bit of the mantissa: the smallest change a double can take.
void flip(double& v) {
  v = std::bit_cast<double>(std::bit_cast<std::uint64_t>(v) ^ 1u);
}

// A sphere sliding on a base under a clump that spins on the `full` integrator, a
// servo-driven lid above: contacts with shear history, dashpots, local damping,
// gravity work and a moving wall, each with a nonzero value to flip.
Simulation scene() {
  SimulationSettings s = scenes::bare_settings();
  s.gravity = Vec3(0, 0, -9.81);
  s.local_damping = 0.3;
  s.damping_ratio = 0.1;
  s.rotation = RotationIntegrator::kFull;
  Simulation sim(s);
  const Material m{1e6, 1e6, 0.5};
  const Index mat = sim.add_material(m);
  sim.add_wall(scenes::plane_wall(Vec3::Zero(), Vec3::UnitZ(), m));
  const Index lid = sim.add_wall(scenes::plane_wall(Vec3(0, 0, 0.07), -Vec3::UnitZ(), m));
  const Index sphere = sim.add_sphere(Vec3(0, 0, 0.0199), 0.02, 2600, mat);
  const std::vector<Vec3> offsets{Vec3(-0.015, 0, 0), Vec3(0.015, 0, 0)};
  const std::vector<double> radii{0.015, 0.015};
  const Index clump =
      sim.add_clump(Vec3(0.015, 0, 0.05), Quat(Eigen::AngleAxisd(0.3, Vec3::UnitY())), offsets,
                    radii, 0.07, Vec3(1e-5, 2e-5, 2e-5), mat);
  Servo servo;
  servo.walls = {lid};
  servo.target_force = [](double) { return 10.0; };
  sim.add_servo(servo);
  sim.set_body_velocity(sphere, Vec3(0.1, 0, 0));
  sim.set_body_angular_velocity(clump, Vec3(1, 2, 3));
  sim.run(20);
  return sim;
}

struct Flip {
  std::string what;
  std::function<void(Simulation&)> apply;
};

}  // namespace

TEST(StateHash, SeesALastBitFlipInEveryReportedQuantity) {
  const Simulation base = scene();
  // Friction history and slip on both lists, so that the flips below have a target.
  ASSERT_FALSE(base.ball_contacts().shear_force.empty());
  ASSERT_FALSE(base.ball_contacts().normal_force.empty());
  ASSERT_FALSE(base.wall_contacts().shear_force.empty());
  ASSERT_FALSE(base.wall_contacts().slip_total.empty());
  ASSERT_GT(base.contacts().ball_contacts + base.contacts().wall_contacts, 1);
  const std::uint64_t h0 = state_hash(base);
  EXPECT_EQ(state_hash(Simulation(base)), h0);  // a copy is the same state
  const auto bodies = [](Simulation& s) -> BodyStore& { return writable(s.bodies()); };
  const auto balls = [](Simulation& s) -> BallStore& { return writable(s.balls()); };
  const std::vector<Flip> flips{
      {"position", [&](Simulation& s) { flip(bodies(s).position[1].z()); }},
      {"velocity", [&](Simulation& s) { flip(bodies(s).velocity[0].x()); }},
      {"angular velocity", [&](Simulation& s) { flip(bodies(s).angular_velocity[1].y()); }},
      {"angular momentum", [&](Simulation& s) { flip(bodies(s).angular_momentum[1].y()); }},
      {"orientation", [&](Simulation& s) { flip(bodies(s).orientation[1].coeffs()[1]); }},
      {"accumulated rotation", [&](Simulation& s) { flip(bodies(s).rotation[1].z()); }},
      {"displacement reference", [&](Simulation& s) { flip(bodies(s).reference_position[0].x()); }},
      {"force", [&](Simulation& s) { flip(bodies(s).force[0].z()); }},
      {"torque", [&](Simulation& s) { flip(bodies(s).torque[1].y()); }},
      {"gravity work", [&](Simulation& s) { flip(bodies(s).gravity_work[0]); }},
      {"damping dissipated", [&](Simulation& s) { flip(bodies(s).damping_dissipated[1]); }},
      {"friction dissipated", [&](Simulation& s) { flip(balls(s).friction_dissipated[0]); }},
      {"viscous dissipated", [&](Simulation& s) { flip(balls(s).viscous_dissipated[0]); }},
      {"slip since the build",
       [&](Simulation& s) { flip(writable(s.wall_contacts()).slip_total[0]); }},
      {"shear history",
       [&](Simulation& s) { flip(writable(s.wall_contacts()).shear_force[0].x()); }},
      {"normal force", [&](Simulation& s) { flip(writable(s.ball_contacts()).normal_force[0]); }},
      {"wall displacement", [&](Simulation& s) { flip(writable(s.walls())[1].displacement.z()); }},
      {"wall velocity", [&](Simulation& s) { flip(writable(s.walls())[1].velocity.z()); }},
      {"servo speed", [&](Simulation& s) { flip(writable(s.servos())[0].speed); }},
  };
  for (const Flip& f : flips) {
    SCOPED_TRACE(f.what);
    Simulation copy = base;
    f.apply(copy);
    EXPECT_NE(state_hash(copy), h0);
  }
}

// The motion hash (for runs whose contact bookkeeping may differ) still sees the
// orientation and the accumulated rotation, the box test's headline measurement.
TEST(StateHash, MotionHashSeesOrientationAndAccumulatedRotation) {
  const Simulation base = scene();
  const std::uint64_t h0 = motion_hash(base.bodies());
  Simulation turned = base, rotated = base;
  flip(writable(turned.bodies()).orientation[1].coeffs()[3]);
  flip(writable(rotated.bodies()).rotation[0].x());
  EXPECT_NE(motion_hash(turned.bodies()), h0);
  EXPECT_NE(motion_hash(rotated.bodies()), h0);
}
