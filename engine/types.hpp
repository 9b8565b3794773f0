// Basic numeric types shared by the whole engine. SI units throughout:
// metres, kilograms, seconds, newtons.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

namespace ballast {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Quat = Eigen::Quaterniond;

// Index types are 32-bit: 2^31 balls is far beyond what fits in memory on the
// machines we target, and halving index width keeps the contact arrays compact.
using Index = std::int32_t;
inline constexpr Index kNoIndex = -1;

inline constexpr double kPi = 3.14159265358979323846;

// The first coordinate of a vector of 3-vectors, as the flat x0 y0 z0 x1 ... array the
// SIMD kernels read; nullptr when it is empty (v.data()->data() would then reach
// through a null pointer: undefined, and caught by -fsanitize=undefined).
inline double* flat(std::vector<Vec3>& v) {
  return v.empty() ? nullptr : v.data()->data();
}
inline const double* flat(const std::vector<Vec3>& v) {
  return v.empty() ? nullptr : v.data()->data();
}

}  // namespace ballast
