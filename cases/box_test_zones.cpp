#include "cases/box_test_zones.hpp"

namespace ballast {

namespace {

void add(ZoneMotion& z, const BoxTestResult& r, std::size_t k) {
  ++z.count;
  z.dz_peak += r.position_peak[k].z() - r.position_start[k].z();
  z.dz_end += r.position_end[k].z() - r.position_start[k].z();
  z.rotation_loading_deg += r.rotation_deg_loading[k];
  z.rotation_unloading_deg += r.rotation_deg_unloading[k];
  z.rotation_cycle_deg += r.rotation_deg_cycle[k];
}

void to_means(ZoneMotion& z) {
  if (z.count == 0) return;
  const double n = double(z.count);
  z.dz_peak /= n;
  z.dz_end /= n;
  z.rotation_loading_deg /= n;
  z.rotation_unloading_deg /= n;
  z.rotation_cycle_deg /= n;
}

}  // namespace

Zones measure_zones(const BoxTestResult& r, double x0, double x1, double surface, double depth) {
  Zones z;
  z.surface = surface;
  z.layer_depth = depth;
  for (std::size_t k = 0; k < r.position_start.size(); ++k) {
    const Vec3& x = r.position_start[k];
    if (x.z() < surface - depth) continue;
    add(x.x() >= x0 && x.x() <= x1 ? z.beneath : z.beside, r, k);
  }
  to_means(z.beneath);
  to_means(z.beside);
  return z;
}

}  // namespace ballast
