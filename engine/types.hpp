// Basic numeric types shared by the whole engine. SI units throughout:
// metres, kilograms, seconds, newtons.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>

namespace ballast {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Quat = Eigen::Quaterniond;

// Index types are 32-bit: 2^31 balls is far beyond what fits in memory on the
// machines we target, and halving index width keeps the contact arrays compact.
using Index = std::int32_t;
inline constexpr Index kNoIndex = -1;

inline constexpr double kPi = 3.14159265358979323846;

}  // namespace ballast
