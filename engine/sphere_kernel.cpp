// Picks the sphere pass's SIMD kernel. The kernels give the scalar pass's bits
// (sphere_kernel.hpp), so the choice moves time only.
#include "engine/sphere_kernel.hpp"

#include <cstdlib>
#include <cstring>

namespace ballast {

bool sphere_kernel_supported(int lanes) {
  if (lanes == 4) return __builtin_cpu_supports("avx2");
  if (lanes == 8) return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512dq");
  return false;
}

int sphere_kernel_best_lanes() {
  static const int lanes = [] {
    const char* want = std::getenv("BALLAST_SIMD");
    const int widest = sphere_kernel_supported(8) ? 8 : sphere_kernel_supported(4) ? 4 : 0;
    if (want != nullptr && std::strcmp(want, "off") == 0) return 0;
    if (want != nullptr && std::strcmp(want, "avx2") == 0) return widest >= 4 ? 4 : 0;
    return widest;
  }();
  return lanes;
}

const char* sphere_kernel_name(int lanes) {
  return lanes == 8 ? "avx512" : lanes == 4 ? "avx2" : "scalar";
}

void sphere_kernel_ball_ball(const SphereKernelView& v, std::int32_t lo, std::int32_t hi,
                             int lanes) {
  if (lanes == 8)
    sphere_kernel_ball_ball_avx512(v, lo, hi);
  else
    sphere_kernel_ball_ball_avx2(v, lo, hi);
}

void sphere_kernel_ball_plane(const SpherePlaneView& v, std::int32_t first, std::int32_t last,
                              int lanes) {
  if (lanes == 8)
    sphere_kernel_ball_plane_avx512(v, first, last);
  else
    sphere_kernel_ball_plane_avx2(v, first, last);
}

std::int32_t sphere_kernel_update(const SphereUpdateView& v, std::int32_t lo, std::int32_t hi,
                                  int lanes, SphereUpdateReport& report) {
  return lanes == 8 ? sphere_kernel_update_avx512(v, lo, hi, report)
                    : sphere_kernel_update_avx2(v, lo, hi, report);
}

}  // namespace ballast
