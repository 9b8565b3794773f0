#include "engine/clump_mass.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "engine/ball_union_integral.hpp"
#include "engine/errors.hpp"

namespace ballast {
namespace {

double ball_volume(double r) {
  return 4.0 / 3.0 * kPi * r * r * r;
}

}  // namespace

void validate_mass_options(const ClumpMassOptions& o) {
  std::ostringstream s;
  if (!(o.density > 0.0 && std::isfinite(o.density))) {
    s << "clump mass parameter 'density' = " << o.density << " is not > 0 (kg/m^3)";
    throw SetupError(s.str());
  }
  if (!(o.accuracy >= 1e-5 && o.accuracy <= 0.1)) {
    s << "clump mass parameter 'accuracy' = " << o.accuracy << " is outside [1e-05, 0.1]";
    throw SetupError(s.str());
  }
}

const char* mass_mode_name(MassMode mode) {
  switch (mode) {
    case MassMode::kSum:
      return "sum";
    case MassMode::kPaper:
      return "paper";
    case MassMode::kUniform:
      return "uniform";
  }
  return "?";
}

MassMode parse_mass_mode(std::string_view name) {
  for (MassMode m : {MassMode::kSum, MassMode::kPaper, MassMode::kUniform}) {
    if (name == mass_mode_name(m)) return m;
  }
  throw SetupError("clump mass parameter 'mass_mode' = '" + std::string(name) +
                   "' is not one of: sum, paper, uniform");
}

MassProperties summed_mass_properties(const std::vector<Vec3>& centres,
                                      const std::vector<double>& radii, double density) {
  MassProperties mp;
  mp.density = density;
  Vec3 moment = Vec3::Zero();
  for (std::size_t p = 0; p < radii.size(); ++p) {
    const double m = density * ball_volume(radii[p]);
    mp.mass += m;              // eq 12
    moment += m * centres[p];  // eq 13
    mp.volume += ball_volume(radii[p]);
  }
  mp.centre = moment / mp.mass;
  for (std::size_t p = 0; p < radii.size(); ++p) {
    const double m = density * ball_volume(radii[p]);
    const Vec3 d = centres[p] - mp.centre;
    // eq 14 (diagonal: own sphere 2/5 m R² plus parallel axis) and eq 15 (products
    // of inertia, which enter the tensor with a minus sign).
    mp.inertia +=
        m * ((0.4 * radii[p] * radii[p] + d.squaredNorm()) * Mat3::Identity() - d * d.transpose());
  }
  return mp;
}

MassProperties clump_mass_properties(const std::vector<Vec3>& centres,
                                     const std::vector<double>& radii, const ClumpMassOptions& o,
                                     double clump_volume) {
  validate_mass_options(o);
  if (centres.empty() || centres.size() != radii.size()) {
    throw SetupError("clump mass properties need as many centres as radii, at least one");
  }
  switch (o.mode) {
    case MassMode::kSum:
      return summed_mass_properties(centres, radii, o.density);
    case MassMode::kPaper: {
      if (!(clump_volume > 0.0)) {
        std::ostringstream s;
        s << "clump mass parameter 'V_clump' = " << clump_volume << " is not > 0 (m^3)";
        throw SetupError(s.str());
      }
      double sum_v = 0.0;
      for (double r : radii) sum_v += ball_volume(r);
      const double rho_m = clump_volume * o.density / sum_v;  // eq 10
      MassProperties mp = summed_mass_properties(centres, radii, rho_m);
      mp.volume = clump_volume;  // so that mass = rho0 · V_clump
      return mp;
    }
    case MassMode::kUniform: {
      const BallUnionMoments u = ball_union_moments(centres, radii, o.accuracy);
      if (!u.converged) {
        std::ostringstream s;
        s << "uniform clump mass: integration of " << radii.size()
          << " balls did not reach accuracy " << o.accuracy << " within its cell budget";
        throw std::runtime_error(s.str());
      }
      MassProperties mp;
      mp.density = o.density;
      mp.volume = u.volume;
      mp.mass = o.density * u.volume;
      mp.centre = u.centroid;
      const Mat3 unit = u.unit_inertia();
      mp.inertia = o.density * unit;
      const double i_min =
          Eigen::SelfAdjointEigenSolver<Mat3>(unit, Eigen::EigenvaluesOnly).eigenvalues()(0);
      mp.relative_error = std::max(u.volume_error / u.volume, u.inertia_error / i_min);
      return mp;
    }
  }
  throw SetupError("clump mass parameter 'mode' has an unknown value");
}

ClumpTemplate to_principal_frame(const std::vector<Vec3>& centres, const std::vector<double>& radii,
                                 const MassProperties& mp, MassMode mode) {
  Eigen::SelfAdjointEigenSolver<Mat3> eig(mp.inertia);
  Mat3 axes = eig.eigenvectors();  // columns, eigenvalues ascending
  for (int k = 0; k < 2; ++k) {
    Eigen::Index big = 0;
    axes.col(k).cwiseAbs().maxCoeff(&big);
    if (axes(big, k) < 0.0) axes.col(k) = -axes.col(k);
  }
  axes.col(2) = axes.col(0).cross(axes.col(1));  // right-handed by construction

  ClumpTemplate t;
  t.radii = radii;
  t.offsets.reserve(centres.size());
  for (const Vec3& c : centres) t.offsets.push_back(axes.transpose() * (c - mp.centre));
  t.mass = mp.mass;
  t.principal_inertia = eig.eigenvalues();
  t.volume = mp.volume;
  t.density = mp.density;
  t.mass_mode = mode;
  t.integration_error = mp.relative_error;
  t.generation_centre = mp.centre;
  t.generation_rotation = axes;
  return t;
}

ClumpTemplate make_clump_template(const ClumpGeometry& g, const ClumpMassOptions& o) {
  const MassProperties mp =
      clump_mass_properties(g.centres, g.radii, o, 4.0 / 3.0 * kPi * std::pow(g.nominal_radius, 3));
  return to_principal_frame(g.centres, g.radii, mp, o.mode);
}

}  // namespace ballast
