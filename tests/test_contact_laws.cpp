// Every contact law of the registry (engine/contact_laws.hpp) against itself: the
// members a law provides must agree with its force, so that the timestep, the
// servo and the energy ledger see the law the force pass runs. Each law is
// checked here without a line of its own; its closed forms are in
// tests/test_law_<name>.cpp.
//
//   overlap_at(Fn(δ)) = δ                  the inverse the servo and the ledger use
//   stiffness(δ).kn = dFn/dδ               the tangent stiffness of the timestep
//   elastic_energy(Fn(δ)) = ∫₀^δ Fn dδ'    the ledger's stored energy
//   one step at shear speed v: |Fs| = stiffness(δ).ks·v·dt, stored Fs²/(2·ks)
//   mix(a, b) = mix(b, a)
//   a sphere scene's normal forces are the law's own (no other law's kernel)
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "cases/box_test.hpp"
#include "engine/contact_laws.hpp"
#include "engine/timestep.hpp"
#include "test_helpers.hpp"

using namespace ballast;

namespace {

// A material every law accepts: the box test's ballast, which fills every member.
const Material kBallast = box_test::ballast_material(0.5);
const Material kSteel = box_test::wall_material(0.3);

// Overlaps from a settled bed's to a hard impact's, m.
const double kOverlaps[] = {1e-8, 1e-7, 1e-6, 1e-5};

template <class Law>
double normal_force(const PairProperties& p, double radius, double overlap) {
  ContactState c{};
  c.overlap = overlap;
  c.normal = {0.0, 0.0, 1.0};
  c.radius = radius;
  c.dt = 1e-6;
  V3 shear{0.0, 0.0, 0.0};
  return Law::template force<false, false>(c, p, shear).normal_force;
}

// Calls check(Law{}, name) for every law in the registry.
template <class F>
void for_every_law(F&& check) {
  for (int law = 0; law < kContactLawCount; ++law) {
    SCOPED_TRACE(std::string(contact_law_name(law)));
    with_contact_law(law, [&](auto l) { check(l); });
  }
}

}  // namespace

TEST(ContactLaws, OverlapAtInvertsTheNormalForce) {
  for_every_law([](auto law) {
    using Law = decltype(law);
    const PairProperties p = Law::mix(kBallast, kBallast);
    for (const double d : kOverlaps) {
      const double fn = normal_force<Law>(p, 0.009, d);
      EXPECT_NEAR(Law::overlap_at(p, 0.009, fn), d, 1e-12 * d) << "overlap " << d;
    }
  });
}

// Central difference with a step of 1e-4·δ: its truncation error is about 1e-8 of
// kn for a power law, its rounding error about 1e-12.
TEST(ContactLaws, StiffnessIsTheNormalForcesDerivative) {
  for_every_law([](auto law) {
    using Law = decltype(law);
    const PairProperties p = Law::mix(kBallast, kSteel);
    for (const double d : kOverlaps) {
      const double h = 1e-4 * d;
      const double slope =
          (normal_force<Law>(p, 0.018, d + h) - normal_force<Law>(p, 0.018, d - h)) / (2 * h);
      const double kn = Law::stiffness(p, 0.018, d).kn;
      EXPECT_NEAR(kn, slope, 1e-6 * slope) << "overlap " << d;
    }
  });
}

// Simpson's rule on 2,000 intervals: exact for the linear law, 1e-9 for δ^1.5
// (whose integrand has an infinite second derivative only at 0).
TEST(ContactLaws, StoredEnergyIsTheNormalForcesIntegral) {
  for_every_law([](auto law) {
    using Law = decltype(law);
    const PairProperties p = Law::mix(kBallast, kBallast);
    for (const double d : kOverlaps) {
      const int n = 2000;
      double sum = normal_force<Law>(p, 0.009, d);  // f(0) = 0
      for (int k = 1; k < n; ++k)
        sum += (k % 2 ? 4.0 : 2.0) * normal_force<Law>(p, 0.009, d * k / n);
      const double work = sum * d / n / 3.0;
      const double stored = Law::elastic_energy(p, 0.009, normal_force<Law>(p, 0.009, d), 0.0);
      EXPECT_NEAR(stored, work, 1e-6 * work) << "overlap " << d;
    }
  });
}

TEST(ContactLaws, OneShearStepLoadsTheTangentSpring) {
  for_every_law([](auto law) {
    using Law = decltype(law);
    const PairProperties p = Law::mix(kBallast, kBallast);
    ContactState c{};
    c.overlap = 1e-6;
    c.normal = {0.0, 0.0, 1.0};
    c.vrel = {1e-4, 0.0, 0.0};
    c.radius = 0.009;
    c.dt = 1e-6;
    V3 shear{0.0, 0.0, 0.0};
    const ContactResult r = Law::template force<true, false>(c, p, shear);
    const double ks = Law::stiffness(p, c.radius, c.overlap).ks;
    ASSERT_LT(ks * 1e-10, p.mu * r.normal_force);  // below the Coulomb cap
    EXPECT_NEAR(shear.x, -ks * 1e-10, 1e-12 * ks * 1e-10);
    // The shear part is a difference of two energies the normal part dominates, so
    // it is good to the normal part's rounding (a few 1e-16 of it) only.
    const double fs2 = shear.x * shear.x;
    const double normal = Law::elastic_energy(p, c.radius, r.normal_force, 0.0);
    EXPECT_NEAR(Law::elastic_energy(p, c.radius, r.normal_force, fs2) - normal, fs2 / (2.0 * ks),
                1e-9 * fs2 / (2.0 * ks) + 1e-15 * normal);
  });
}

TEST(ContactLaws, MixingIsSymmetric) {
  for_every_law([](auto law) {
    using Law = decltype(law);
    const PairProperties ab = Law::mix(kBallast, kSteel), ba = Law::mix(kSteel, kBallast);
    EXPECT_EQ(ab.normal, ba.normal);
    EXPECT_EQ(ab.shear, ba.shear);
    EXPECT_EQ(ab.mu, ba.mu);
  });
}

// A scene of spheres without dashpots is the one the SIMD kernel may take; it
// evaluates the linear law only (LinearLaw::kSphereKernel). Under every law, every
// touching contact's normal force must be that law's for the contact's overlap at
// the start of the step: a law sent through another's kernel fails here.
TEST(ContactLaws, ASphereSceneRunsItsOwnLaw) {
  for_every_law([](auto law) {
    using Law = decltype(law);
    SimulationSettings s = scenes::bare_settings();
    s.contact_law = std::string(Law::kName);
    s.gravity = Vec3(0, 0, -200.0);
    s.local_damping = 0.7;  // a resting pile rather than bouncing balls
    Simulation sim(s);
    const double r = 0.02;
    const Index mat = sim.add_material(kBallast);
    sim.add_wall(scenes::plane_wall(Vec3(0, 0, -0.5), Vec3::UnitZ(), kSteel));
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j)
        for (int k = 0; k < 3; ++k)
          sim.add_sphere(Vec3(-0.08 + 0.041 * i + 0.002 * k, -0.08 + 0.041 * j, -0.47 + 0.041 * k),
                         r, 2600.0, mat);
    while (sim.time() < 0.05) sim.step();
    const std::vector<Vec3> before = sim.balls().position;
    sim.step();
    if (!Law::kSphereKernel) {
      EXPECT_EQ(sim.sphere_kernel_lanes(), 0);
    }
    const PairProperties p = Law::mix(kBallast, kBallast);
    const ContactList& bc = sim.ball_contacts();
    int touching = 0;
    for (Index c = 0; c < bc.size(); ++c) {
      if (!bc.active[c]) continue;
      ++touching;
      const double overlap = 2 * r - (before[bc.a[c]] - before[bc.b[c]]).norm();
      const double expected = normal_force<Law>(p, 0.5 * r, overlap);
      EXPECT_NEAR(bc.normal_force[c], expected, 1e-9 * expected) << "contact " << c;
    }
    EXPECT_GT(touching, 10);
  });
}

// What a scene estimates up front (lone_sphere_timestep, cases/scene_bounds.cpp) is
// what the engine estimates for the same sphere alone: under every law, the bound a
// scene puts on its steps is the engine's own number, not a second formula.
TEST(ContactLaws, LoneSphereTimestepIsTheEnginesForOneFreeSphere) {
  for_every_law([](auto law) {
    using Law = decltype(law);
    SimulationSettings s = scenes::bare_settings();
    s.contact_law = std::string(Law::kName);
    Simulation sim(s);
    const double r = 0.018, rho = 2600.0;
    sim.add_sphere(Vec3::Zero(), r, rho, sim.add_material(kBallast));
    sim.prepare();
    const double lone =
        lone_sphere_timestep(kBallast, r, rho, contact_law_index(Law::kName), s.max_speed);
    EXPECT_NEAR(lone, sim.critical_dt(), 1e-12 * lone);
  });
}
