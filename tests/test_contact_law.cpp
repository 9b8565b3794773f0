// The linear contact law's shear history as the contact plane turns
// (engine/contact_law.hpp, spring_dashpot_contact): the stored shear force is projected into the
// new plane and rescaled to its old magnitude, except where the rescale factor rounds to 1 in
// double precision, where it is skipped. Closed-form checks, no scene.
#include <gtest/gtest.h>

#include <cmath>

#include "engine/law_linear.hpp"

namespace ballast {
namespace {

// A resting contact (no relative velocity) whose normal has turned by `angle` rad,
// in the x–z plane, away from the plane its shear force of `shear` N lies in.
struct Turned {
  V3 shear_after;
  V3 normal;
};

Turned turn_contact(double angle, double shear) {
  ContactState c{};
  c.overlap = 1e-6;  // m: a normal force of 5 N at kn = 5e6 N/m
  c.normal = {std::sin(angle), 0.0, std::cos(angle)};
  c.vrel = {0.0, 0.0, 0.0};
  c.dt = 1e-6;
  const PairProperties p{5e6, 5e6, 1e6};  // mu = 1e6: no Coulomb cap, only the rotation acts
  V3 f{shear, 0.0, 0.0};                  // tangential to the old normal (0, 0, 1)
  LinearLaw::force<true, false>(c, p, f);
  return {f, c.normal};
}

double norm(const V3& v) {
  return std::sqrt(dot(v, v));
}

TEST(ContactLaw, TurnedShearForceKeepsItsMagnitudeAndLiesInTheNewPlane) {
  // The bare projection would lose 1 - cos(angle) ≈ angle²/2 of the force: 0.5 % at
  // 0.1 rad, 5e-15 at 1e-7 rad, far above the 4e-16 allowed here. A skip threshold
  // looser than q = 1e-14 would therefore fail the 1e-7 case; at 1e-9 rad (a settled
  // bed's step) the factor rounds to 1 and the projection alone must already hold
  // the magnitude to rounding.
  for (const double angle : {0.1, 1e-3, 1e-5, 1e-7, 1e-9}) {
    const Turned t = turn_contact(angle, 2.0);
    EXPECT_NEAR(norm(t.shear_after), 2.0, 4e-16 * 2.0) << "angle " << angle;
    EXPECT_NEAR(dot(t.shear_after, t.normal), 0.0, 4e-16 * 2.0) << "angle " << angle;
  }
}

}  // namespace
}  // namespace ballast
