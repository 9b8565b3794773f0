// Clump mass properties: the three modes against closed forms and against an
// independent Monte Carlo integral, and the uniform-mode integrator's accuracy
// against its requested and reported error.
#include <gtest/gtest.h>
#include <omp.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <random>
#include <stdexcept>
#include <string>

#include "cases/clump_presets.hpp"
#include "engine/ball_union_integral.hpp"
#include "engine/clump_batch.hpp"
#include "engine/clump_mass.hpp"
#include "test_helpers.hpp"

namespace ballast {
using ballast::test_support::expect_error;

namespace {

constexpr double kAccuracy = 0.005;  // the accuracy the issue asks for (0.5%)

using scenes::sphere_volume;

// Union volume of two balls: V1 + V2 minus the lens (dem-facts.md, "Porosity").
double two_ball_union_volume(double big_r, double r, double d) {
  const double lens =
      kPi * std::pow(big_r + r - d, 2) *
      (d * d + 2 * d * r - 3 * r * r + 2 * d * big_r + 6 * r * big_r - 3 * big_r * big_r) /
      (12 * d);
  return sphere_volume(big_r) + sphere_volume(r) - lens;
}

Vec3 sorted(Vec3 v) {
  std::sort(v.data(), v.data() + 3);
  return v;
}

// A rotation with no special axis, so that no ball lines up with the integration grid.
Mat3 generic_rotation() {
  return Eigen::AngleAxisd(0.7, Vec3(1.0, 2.0, -0.5).normalized()).toRotationMatrix();
}

TEST(UnionIntegral, OneSphereVolumeAndInertia) {
  const double r = 0.018;
  for (double accuracy : {0.02, 0.01, kAccuracy, 0.002}) {
    const BallUnionMoments u = integrate_ball_union({Vec3(0.01, -0.02, 0.003)}, {r}, accuracy);
    ASSERT_TRUE(u.converged);
    const double v = sphere_volume(r);
    EXPECT_LE(std::abs(u.volume - v), u.volume_error) << accuracy;  // the estimate bounds it
    EXPECT_LE(u.volume_error, accuracy * u.volume * (1 + 1e-9));
    const Vec3 moments =
        sorted(Eigen::SelfAdjointEigenSolver<Mat3>(u.unit_inertia()).eigenvalues());
    const double exact = 0.4 * v * r * r;  // (2/5) m r² per unit density
    for (int k = 0; k < 3; ++k) {
      EXPECT_LE(std::abs(moments[k] - exact), u.inertia_error) << accuracy;
      EXPECT_LE(std::abs(moments[k] - exact), accuracy * exact) << accuracy;
    }
    EXPECT_LT((u.centroid - Vec3(0.01, -0.02, 0.003)).norm(), accuracy * r);
  }
}

TEST(UnionIntegral, TwoOverlappingSpheresMatchTheLensFormula) {
  const double big_r = 0.02, r = 0.012;
  for (double d : {0.009, 0.015, 0.024, 0.030}) {
    const Vec3 axis = generic_rotation() * Vec3::UnitX();
    const BallUnionMoments u =
        integrate_ball_union({Vec3::Zero(), d * axis}, {big_r, r}, kAccuracy);
    const double exact = two_ball_union_volume(big_r, r, d);
    EXPECT_LE(std::abs(u.volume / exact - 1.0), kAccuracy) << "d = " << d;
    EXPECT_LE(std::abs(u.volume - exact), u.volume_error) << "d = " << d;
  }
}

// Unit-density inertia of two equal balls of radius r centred at ±h on an axis:
// integrals over disc slices of the half x > 0 (the ball at +h cut by x = 0 when
// they overlap), doubled. Polynomial integrands, integrated in closed form.
struct DumbbellInertia {
  double axial, transverse;
};
DumbbellInertia dumbbell_inertia(double r, double h) {
  // Slice at x has disc radius² ρ²(x) = r² - (x - h)², x in [lo, h + r].
  const double lo = std::max(0.0, h - r), hi = h + r;
  // Antiderivatives in u = x - h of ρ⁴ = (r² - u²)², ρ² x² = (r² - u²)(u + h)².
  auto rho4 = [r](double u) {
    return std::pow(r, 4) * u - 2.0 / 3.0 * r * r * std::pow(u, 3) + std::pow(u, 5) / 5.0;
  };
  auto rho2x2 = [r, h](double u) {
    // (r² - u²)(u² + 2hu + h²) = r²h² + 2r²h u + (r² - h²) u² - 2h u³ - u⁴
    return r * r * h * h * u + r * r * h * u * u + (r * r - h * h) * std::pow(u, 3) / 3.0 -
           h * std::pow(u, 4) / 2.0 - std::pow(u, 5) / 5.0;
  };
  const double i4 = rho4(hi - h) - rho4(lo - h), i2 = rho2x2(hi - h) - rho2x2(lo - h);
  // Disc: axial ∫ (π/2) ρ⁴ dx; transverse ∫ (π/4 ρ⁴ + π ρ² x²) dx.
  return {2.0 * kPi / 2.0 * i4, 2.0 * (kPi / 4.0 * i4 + kPi * i2)};
}

TEST(ClumpMass, SymmetricDumbbellMatchesItsAnalyticInertia) {
  const double r = 0.015, density = 2600.0;
  for (double h : {0.006, 0.012, 0.02}) {  // overlapping, touching-ish, apart
    const Vec3 axis = generic_rotation() * Vec3::UnitZ();
    const std::vector<Vec3> centres = {h * axis, -h * axis};
    ClumpMassOptions o;
    o.density = density;
    const ClumpTemplate t = to_principal_frame(
        centres, {r, r}, clump_mass_properties(centres, {r, r}, o, 0.0), MassMode::kUniform);
    const DumbbellInertia exact = dumbbell_inertia(r, h);
    EXPECT_NEAR(t.principal_inertia[0], density * exact.axial, kAccuracy * density * exact.axial);
    EXPECT_NEAR(t.principal_inertia[1], density * exact.transverse,
                kAccuracy * density * exact.transverse);
    EXPECT_NEAR(t.principal_inertia[2], density * exact.transverse,
                kAccuracy * density * exact.transverse);
    // The smallest moment's axis is the dumbbell's axis.
    EXPECT_NEAR(std::abs(t.generation_rotation.col(0).dot(axis)), 1.0, 1e-6);
    if (h >= r) {
      // Apart: the closed form is two spheres with parallel axes.
      const double m = density * sphere_volume(r);
      EXPECT_NEAR(density * exact.axial, 2 * 0.4 * m * r * r, 1e-12 * m * r * r);
      EXPECT_NEAR(density * exact.transverse, 2 * (0.4 * m * r * r + m * h * h), 1e-12 * m * r * r);
    }
  }
}

TEST(ClumpMass, UniformAgreesWithSumForBallsThatDoNotOverlap) {
  // Three separate balls of different sizes, asymmetric: sum mode is exact here, so
  // the integrator must agree with it within its accuracy.
  const std::vector<Vec3> centres = {Vec3(0, 0, 0), Vec3(0.04, 0.01, 0), Vec3(-0.01, 0.035, 0.02)};
  const std::vector<double> radii = {0.015, 0.01, 0.008};
  const double rho = 2600.0;
  const MassProperties ms = summed_mass_properties(centres, radii, rho);
  const BallUnionMoments u = integrate_ball_union(centres, radii, kAccuracy);
  EXPECT_NEAR(rho * u.volume, ms.mass, kAccuracy * ms.mass);
  EXPECT_LE(std::abs(rho * u.volume - ms.mass), rho * u.volume_error);
  EXPECT_LT((u.centroid - ms.centre).norm(), kAccuracy * 0.015);
  const Vec3 iu = Eigen::SelfAdjointEigenSolver<Mat3>(rho * u.unit_inertia()).eigenvalues();
  const Vec3 is = Eigen::SelfAdjointEigenSolver<Mat3>(ms.inertia).eigenvalues();
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(iu[k], is[k], kAccuracy * is[k]);
    EXPECT_LE(std::abs(iu[k] - is[k]), rho * u.inertia_error);
  }
  // Uniform mode itself skips the integration when nothing overlaps: exactly sum.
  const MassProperties mu = clump_mass_properties(centres, radii, ClumpMassOptions{}, 0.0);
  EXPECT_NEAR(mu.mass, ms.mass, 1e-14 * ms.mass);
  EXPECT_EQ(mu.relative_error, 0.0);
  EXPECT_LT((mu.inertia - ms.inertia).norm(), 1e-12 * ms.inertia.norm());
}

TEST(ClumpMass, SumModeFollowsEqs12To15) {
  // Two balls on the x axis: m = Σm, x_G = Σ m x / m, I by parallel axes.
  const double rho = 2600.0, r1 = 0.02, r2 = 0.01;
  const std::vector<Vec3> centres = {Vec3(0, 0, 0), Vec3(0.02, 0, 0)};
  const MassProperties mp = summed_mass_properties(centres, {r1, r2}, rho);
  const double m1 = rho * sphere_volume(r1), m2 = rho * sphere_volume(r2);
  EXPECT_NEAR(mp.mass, m1 + m2, 1e-15);
  const double xg = m2 * 0.02 / (m1 + m2);
  EXPECT_NEAR(mp.centre.x(), xg, 1e-15);
  const double ixx = 0.4 * (m1 * r1 * r1 + m2 * r2 * r2);
  const double iyy = ixx + m1 * xg * xg + m2 * (0.02 - xg) * (0.02 - xg);
  EXPECT_NEAR(mp.inertia(0, 0), ixx, 1e-12 * ixx);
  EXPECT_NEAR(mp.inertia(1, 1), iyy, 1e-12 * iyy);
  EXPECT_NEAR(mp.inertia(2, 2), iyy, 1e-12 * iyy);
  EXPECT_NEAR(mp.inertia(0, 1), 0.0, 1e-12 * ixx);
}

TEST(ClumpMass, PaperModeGivesTheNominalSphereMassWithScaledDensity) {
  const ClumpPreset preset = load_clump_preset("table2/sample2");
  std::mt19937_64 rng = clump_rng(1, 0);
  const ClumpGeometry g = generate_clump(preset.params, rng);
  ClumpMassOptions paper, sum;
  paper.mode = MassMode::kPaper;
  sum.mode = MassMode::kSum;
  const ClumpTemplate tp = make_clump_template(g, paper);
  const ClumpTemplate ts = make_clump_template(g, sum);
  const double v_clump = sphere_volume(0.5 * preset.params.nominal_diameter);
  EXPECT_NEAR(tp.mass, 2600.0 * v_clump, 1e-12 * tp.mass);  // eq 10: ρm ΣVi = ρ0 V_clump
  EXPECT_NEAR(tp.density, 2600.0 * v_clump / ts.volume, 1e-9 * tp.density);
  // Same geometry, density scaled: inertia scales with it and the frame is the same.
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(tp.principal_inertia[k], ts.principal_inertia[k] * tp.mass / ts.mass,
                1e-9 * tp.principal_inertia[k]);
  }
  EXPECT_LT((tp.generation_centre - ts.generation_centre).norm(), 1e-15);
}

TEST(ClumpMass, TemplatesAreInARightHandedPrincipalFrameAboutTheCentreOfMass) {
  const ClumpParams q = load_clump_preset("table2/sample2").params;
  for (MassMode mode : {MassMode::kSum, MassMode::kPaper, MassMode::kUniform}) {
    ClumpMassOptions o;
    o.mode = mode;
    for (int i = 0; i < 5; ++i) {
      std::mt19937_64 rng = clump_rng(2, i);
      const ClumpGeometry g = generate_clump(q, rng);
      const ClumpTemplate t = make_clump_template(g, o);
      const Mat3& rot = t.generation_rotation;
      EXPECT_NEAR(rot.determinant(), 1.0, 1e-12);
      EXPECT_LT((rot.transpose() * rot - Mat3::Identity()).norm(), 1e-12);
      EXPECT_LE(t.principal_inertia[0], t.principal_inertia[1]);
      EXPECT_LE(t.principal_inertia[1], t.principal_inertia[2]);
      for (std::size_t b = 0; b < g.radii.size(); ++b) {
        EXPECT_LT((t.generation_centre + rot * t.offsets[b] - g.centres[b]).norm(), 1e-15);
      }
      // Recomputed in the template's own frame, the inertia tensor is diagonal with
      // the stored moments and the centre of mass sits at the origin.
      const MassProperties again = clump_mass_properties(t.offsets, t.radii, o, t.volume);
      const double scale = t.principal_inertia[2];
      EXPECT_LT(again.centre.norm(), (mode == MassMode::kUniform ? kAccuracy : 1e-12) * 0.02);
      const double tol = mode == MassMode::kUniform ? kAccuracy : 1e-12;
      for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 3; ++c) {
          const double expected = r == c ? t.principal_inertia[r] : 0.0;
          EXPECT_NEAR(again.inertia(r, c), expected, tol * scale);
        }
      }
    }
  }
}

TEST(ClumpMass, UniformModeMeetsItsAccuracyOnGeneratedClumps) {
  // Against the same integrator at 50x the accuracy, on Table 2 Sample 2 clumps.
  const ClumpParams q = load_clump_preset("table2/sample2").params;
  ClumpMassOptions fine, coarse;
  fine.accuracy = kAccuracy / 50;
  for (int i = 0; i < 12; ++i) {
    std::mt19937_64 rng = clump_rng(5, i);
    const ClumpGeometry g = generate_clump(q, rng);
    const ClumpTemplate ref = make_clump_template(g, fine);
    const ClumpTemplate t = make_clump_template(g, coarse);
    EXPECT_LE(t.integration_error, kAccuracy * (1 + 1e-9));
    const double reference_error = ref.integration_error;  // <= kAccuracy / 50
    EXPECT_LE(std::abs(t.mass / ref.mass - 1.0), t.integration_error + reference_error);
    for (int k = 0; k < 3; ++k) {
      EXPECT_LE(std::abs(t.principal_inertia[k] / ref.principal_inertia[k] - 1.0),
                t.integration_error + reference_error);
    }
  }
}

TEST(ClumpMass, BatchIsBitIdenticalOnOneAndTwoThreads) {
  const ClumpParams q = load_clump_preset("table2/sample2").params;
  const ClumpMassOptions o;
  test_support::ScopedThreads threads(1);
  const std::vector<ClumpTemplate> one = generate_clump_templates(q, o, 40, 99);
  threads.set(2);
  const std::vector<ClumpTemplate> two = generate_clump_templates(q, o, 40, 99);
  ASSERT_EQ(one.size(), two.size());
  for (std::size_t i = 0; i < one.size(); ++i) {
    EXPECT_EQ(one[i].mass, two[i].mass);
    EXPECT_EQ(one[i].principal_inertia, two[i].principal_inertia);
    EXPECT_EQ(one[i].offsets, two[i].offsets);
    EXPECT_EQ(one[i].radii, two[i].radii);
  }
  // The batch is the single-clump path, clump i drawn from clump_rng(seed, i).
  std::mt19937_64 rng = clump_rng(99, 7);
  const ClumpTemplate seven = make_clump_template(generate_clump(q, rng), o);
  EXPECT_EQ(seven.mass, one[7].mass);
}

// ---- An independent Monte Carlo estimate of a clump's mass properties ----
//
// Points drawn uniformly in the clump's bounding box (fixed-seed mt19937_64) stand
// for volume: a point inside the union of the balls samples the uniform mode; a
// point weighted by the number of balls that hold it samples the sum and paper
// modes, where every ball is a whole solid sphere and overlaps count once per ball.
// Nothing of the engine is used. The draws come in batches, and the scatter of the
// batch estimates gives the standard error of each compared figure, whatever
// non-linear function of the sums it is (mass, centre, a rotated tensor component).

// Five overlapping balls of unequal radii, none in a symmetric position, turned and
// shifted so that no principal axis is a coordinate axis (m). The second lies
// mostly inside the first, so the union's centroid is 0.7 mm from the r³-weighted
// centre, which counts that overlap twice.
struct Clump {
  std::vector<Vec3> centres;
  std::vector<double> radii;
};
Clump off_axis_clump() {
  const std::vector<Vec3> local = {Vec3(0, 0, 0), Vec3(0.008, 0.003, 0), Vec3(-0.006, 0.013, 0.004),
                                   Vec3(0.004, -0.006, 0.012), Vec3(0.020, 0.006, -0.004)};
  Clump c;
  c.radii = {0.014, 0.010, 0.008, 0.007, 0.006};
  for (const Vec3& x : local) {
    c.centres.push_back(Vec3(0.003, -0.002, 0.005) + generic_rotation() * x);
  }
  return c;
}

// Σw, Σw·x and Σw·x xᵀ over sample points, x measured from the box centre (m).
struct WeightedSums {
  double w = 0.0;
  Vec3 x = Vec3::Zero();
  Mat3 xx = Mat3::Zero();
  void add(double weight, const Vec3& p) {
    w += weight;
    x += weight * p;
    xx += weight * p * p.transpose();
  }
  void add(const WeightedSums& o) {
    w += o.w;
    x += o.x;
    xx += o.xx;
  }
};

// What some sums stand for: volume (m³), centre (m), ∫(x − g)(x − g)ᵀ dV (m⁵).
struct VolumeMoments {
  double volume;
  Vec3 centre;
  Mat3 second;
};

struct Samples {
  Vec3 mid;                                 // box centre, m
  double point_volume;                      // box volume / points per batch, m³
  std::vector<WeightedSums> union_batches;  // weight 1 inside the union
  std::vector<WeightedSums> ball_batches;   // weight: how many balls hold the point

  VolumeMoments moments(const WeightedSums& s, int batches = 1) const {
    const double dv = point_volume / batches;
    const Vec3 g = s.x / s.w;
    return {dv * s.w, mid + g, dv * (s.xx - s.w * g * g.transpose())};
  }
};

// 64 batches of 2^18 points, 1.7e7 in all: 0.8 s here. For the clump above, 33 %
// fall inside the union, and the standard errors are 3.3e-4 of the mass, 4.2e-4 to
// 5.0e-4 of the principal moments and 3.2e-6 m for the centre (uniform mode).
Samples sample_clump(const Clump& c) {
  constexpr int kBatches = 64;
  constexpr long kPerBatch = 1L << 18;
  Vec3 lo = Vec3::Constant(INFINITY), hi = Vec3::Constant(-INFINITY);
  for (std::size_t b = 0; b < c.radii.size(); ++b) {
    lo = lo.cwiseMin(c.centres[b] - Vec3::Constant(c.radii[b]));
    hi = hi.cwiseMax(c.centres[b] + Vec3::Constant(c.radii[b]));
  }
  Samples s{0.5 * (lo + hi), (hi - lo).prod() / kPerBatch, {}, {}};
  const Vec3 half = 0.5 * (hi - lo);
  std::mt19937_64 rng(20240607);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  s.union_batches.resize(kBatches);
  s.ball_batches.resize(kBatches);
  for (int batch = 0; batch < kBatches; ++batch) {
    for (long k = 0; k < kPerBatch; ++k) {
      const Vec3 p(half.x() * u(rng), half.y() * u(rng), half.z() * u(rng));
      int holders = 0;
      for (std::size_t b = 0; b < c.radii.size(); ++b) {
        holders += (s.mid + p - c.centres[b]).squaredNorm() < c.radii[b] * c.radii[b];
      }
      if (holders > 0) {
        s.union_batches[batch].add(1.0, p);
        s.ball_batches[batch].add(holders, p);
      }
    }
  }
  return s;
}

// The figures compared: mass (kg), centre of mass (m), and the inertia tensor
// (kg·m²) in the engine's principal frame: its diagonal, then its off-diagonal
// elements, which are zero for the engine.
constexpr int kCompared = 10;
using Figures = std::array<double, kCompared>;
const std::array<const char*, kCompared> kFigureNames = {
    "mass", "centre x", "centre y", "centre z", "I_11", "I_22", "I_33", "I_12", "I_13", "I_23"};

Figures figures(const VolumeMoments& m, double density, const Mat3& axes) {
  const Mat3 inertia = density * (m.second.trace() * Mat3::Identity() - m.second);
  const Mat3 j = axes.transpose() * inertia * axes;
  return {density * m.volume,
          m.centre.x(),
          m.centre.y(),
          m.centre.z(),
          j(0, 0),
          j(1, 1),
          j(2, 2),
          j(0, 1),
          j(0, 2),
          j(1, 2)};
}

Figures engine_figures(const ClumpTemplate& t) {
  const Vec3& g = t.generation_centre;
  const Vec3& i = t.principal_inertia;
  return {t.mass, g.x(), g.y(), g.z(), i[0], i[1], i[2], 0.0, 0.0, 0.0};
}

// The Monte Carlo figures from all points and, from the batches' scatter, their
// standard errors. density: kg/m³ from the moments (the paper mode's depends on ΣV).
struct Estimate {
  Figures value{}, sigma{};
};
template <class Density>
Estimate estimate(const Samples& s, const std::vector<WeightedSums>& batches, Density density,
                  const Mat3& axes) {
  WeightedSums all;
  for (const WeightedSums& b : batches) all.add(b);
  const int n = static_cast<int>(batches.size());
  const VolumeMoments pooled = s.moments(all, n);
  Estimate e;
  e.value = figures(pooled, density(pooled), axes);
  std::vector<Figures> per_batch;
  Figures mean{};
  for (const WeightedSums& b : batches) {
    const VolumeMoments m = s.moments(b);
    per_batch.push_back(figures(m, density(m), axes));
    for (int k = 0; k < kCompared; ++k) mean[k] += per_batch.back()[k] / n;
  }
  for (int k = 0; k < kCompared; ++k) {
    double square = 0.0;
    for (const Figures& f : per_batch) square += (f[k] - mean[k]) * (f[k] - mean[k]);
    e.sigma[k] = std::sqrt(square / (n - 1) / n);  // standard error of the mean of n
  }
  return e;
}

// Every figure within 5 standard errors of the estimate, plus `allowance` (the
// engine's own error bound). With σ estimated from 64 batches (Student t, 63
// degrees of freedom) a 5σ miss by chance has a probability of 5e-6 per figure,
// 5e-5 for the 10 of a mode; the seed is fixed, so the test is deterministic
// anyway. The standard errors must stay small, or the comparison would say
// nothing: at most 1e-3 of the mass and of the largest moment, and 1e-5 m for the
// centre (measured: at most 3.7e-4, 5.0e-4 and 3.2e-6 m).
void expect_within_sampling_error(const char* mode, const Figures& engine, const Estimate& mc,
                                  const Figures& allowance) {
  double worst = 0.0;  // the largest |engine − Monte Carlo| as a fraction of its bound
  for (int k = 0; k < kCompared; ++k) {
    const double difference = engine[k] - mc.value[k];
    const double bound = 5.0 * mc.sigma[k] + allowance[k];
    worst = std::max(worst, std::abs(difference) / bound);
    EXPECT_LE(std::abs(difference), bound)
        << mode << ", " << kFigureNames[k] << ": engine " << engine[k] << ", Monte Carlo "
        << mc.value[k] << " ± " << mc.sigma[k];
    std::printf("%-8s %-8s engine % .6e  Monte Carlo % .6e ± %.2e  (%+.2f σ)\n", mode,
                kFigureNames[k], engine[k], mc.value[k], mc.sigma[k], difference / mc.sigma[k]);
  }
  std::printf("%-8s largest difference: %.0f %% of its bound\n", mode, 100.0 * worst);
  const double largest_moment = std::max({mc.value[4], mc.value[5], mc.value[6]});
  EXPECT_LT(mc.sigma[0], 1e-3 * mc.value[0]) << mode;
  for (int k = 1; k <= 3; ++k) EXPECT_LT(mc.sigma[k], 1e-5) << mode;
  for (int k = 4; k < kCompared; ++k) EXPECT_LT(mc.sigma[k], 1e-3 * largest_moment) << mode;
}

// Measured: every figure within 2.2σ, the largest difference 44 % of its bound.
// The centre's −2.2σ in y is the sampling's: the exact sum mode, on the same
// points, is off by −2.5σ there too.
//
// One-line mutations of the engine this test fails under (applied and rebuilt;
// the largest difference as a multiple of its bound), the first two caught by no
// other test:
//  - ball_union_integral.cpp, UnionIntegrator::run: centroid = the reference point
//    (the r³-weighted centre, as if overlaps counted twice) instead of
//    reference + g: 42×.
//  - the same: the second moment not moved to the centroid (− V·g gᵀ dropped):
//    1.9× (g is 0.7 mm, see off_axis_clump).
//  - column(): every chord flushed on its own, `if (true)` for the merge test
//    (overlaps counted twice, the sum mode): 166×; hi = the next chord's upper end
//    instead of the larger one (a chord inside another cuts the column): 30×;
//    ∫z² dz as d·(hi² + lo²)/3: 120×; the chord's half-length from dx² alone: 190×.
//  - clump_mass.cpp: inertia = ρ·(second moment) instead of ρ·(tr M·𝟙 − M): 259×;
//    to_principal_frame: moments descending against ascending axes: 119×; the
//    eigenvector matrix transposed: 111×.
// Not caught: column_moments' in-cell term s²/3 → s²/12 (a 9e-6 change, 50 times
// below one σ); the frame's handedness (axis signs do not enter here;
// TemplatesAreInARightHandedPrincipalFrameAboutTheCentreOfMass catches it).
TEST(ClumpMass, UniformModeAgreesWithMonteCarloOnAnOffAxisClump) {
  const Clump c = off_axis_clump();
  ClumpMassOptions o;
  // Finer than the default 0.005, so that the engine's own error (1e-4 of the
  // volume and moments, its estimate) is small beside the sampling error (5σ ≈
  // 1.6e-3 to 2.5e-3); it is added to the tolerance all the same. 2e-5 runs out
  // of cells for this clump (ball_union_integral.cpp, kMaxCells).
  o.accuracy = 1e-4;
  const MassProperties mp = clump_mass_properties(c.centres, c.radii, o, 0.0);
  const ClumpTemplate t = to_principal_frame(c.centres, c.radii, mp, MassMode::kUniform);
  ASSERT_GT(t.integration_error, 0.0);  // the union was integrated, not summed
  const Samples s = sample_clump(c);
  const Estimate mc = estimate(
      s, s.union_batches, [&](const VolumeMoments&) { return o.density; }, t.generation_rotation);
  // The reported error bounds the relative error of the mass and, in spectral norm,
  // of the inertia tensor relative to its smallest moment (ball_union_integral.hpp);
  // the centre has no bound of its own and none is allowed.
  const double tensor = t.integration_error * t.principal_inertia[0];
  const Figures allowance = {
      t.integration_error * t.mass, 0.0, 0.0, 0.0, tensor, tensor, tensor, tensor, tensor, tensor};
  expect_within_sampling_error("uniform", engine_figures(t), mc, allowance);
}

// Sum (eqs 12-15) and paper (the same with ρ_m = ρ0·V_clump/ΣV_i, eq 10) against
// the same points weighted by how many balls hold them: closed forms, so no
// allowance beyond the sampling error. Measured: within 2.5σ, the largest
// difference 49 % of its bound.
//
// One-line mutations of clump_mass.cpp this test fails under (applied and rebuilt;
// the largest difference as a multiple of its bound, sum / paper). Each also fails
// a test above (SumModeFollowsEqs12To15, PaperModeGivesTheNominalSphereMass...,
// TemplatesAre...); those check two or three balls against the same formulas,
// this one a clump with no symmetry against an independent integral.
//  - summed_mass_properties: the parallel-axis |d|² dropped: 367× / 473×; −d dᵀ
//    dropped: 114× / 150×; 2/5 R² → 3/5 R²: 167× / 216×; the centre as Σx_p / n
//    instead of Σm_p x_p / m: 5e6×.
//  - eq 10: ρ_m = ρ0: 7e11× for the paper mass (exact on both sides, so bounded
//    by round-off), and its moments scaled by ΣV_i / V_clump.
//  - to_principal_frame: moments descending against ascending axes: 140×; the
//    eigenvector matrix transposed: 132×.
TEST(ClumpMass, SumAndPaperModesAgreeWithMonteCarloOnAnOffAxisClump) {
  const Clump c = off_axis_clump();
  const double v_clump = sphere_volume(0.02);  // a nominal sphere of 40 mm, m³
  ClumpMassOptions sum, paper;
  sum.mode = MassMode::kSum;
  paper.mode = MassMode::kPaper;
  const ClumpTemplate ts = to_principal_frame(
      c.centres, c.radii, clump_mass_properties(c.centres, c.radii, sum, 0.0), MassMode::kSum);
  const ClumpTemplate tp = to_principal_frame(
      c.centres, c.radii, clump_mass_properties(c.centres, c.radii, paper, v_clump),
      MassMode::kPaper);
  const Samples s = sample_clump(c);
  const Estimate mc_sum = estimate(
      s, s.ball_batches, [&](const VolumeMoments&) { return sum.density; }, ts.generation_rotation);
  expect_within_sampling_error("sum", engine_figures(ts), mc_sum, Figures{});
  const Estimate mc_paper = estimate(
      s, s.ball_batches, [&](const VolumeMoments& m) { return paper.density * v_clump / m.volume; },
      tp.generation_rotation);
  // The paper mass is ρ0·V_clump on both sides: they differ by round-off only.
  Figures round_off{};
  round_off[0] = 1e-12 * tp.mass;
  expect_within_sampling_error("paper", engine_figures(tp), mc_paper, round_off);
}

TEST(ClumpMass, BadOptionsAreRejectedNamingTheField) {
  auto expect_names = [](const ClumpMassOptions& o, const std::string& field) {
    expect_error<std::invalid_argument>([&] { validate_mass_options(o); }, {"'" + field + "'"});
  };
  ClumpMassOptions o;
  o.density = 0.0;
  expect_names(o, "density");
  o = ClumpMassOptions{};
  o.accuracy = 0.5;
  expect_names(o, "accuracy");
  o.accuracy = 0.0;
  expect_names(o, "accuracy");
  EXPECT_EQ(parse_mass_mode("paper"), MassMode::kPaper);
  expect_error<std::invalid_argument>([] { parse_mass_mode("heavy"); }, {"'mass_mode'", "uniform"});
  EXPECT_THROW(integrate_ball_union({Vec3::Zero()}, {-1.0}, kAccuracy), std::invalid_argument);
  EXPECT_THROW(integrate_ball_union({Vec3::Zero()}, {1.0, 2.0}, kAccuracy), std::invalid_argument);
}

}  // namespace
}  // namespace ballast
