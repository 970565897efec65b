#pragma once

#include <Eigen/Geometry>
#include <cmath>

namespace ply_slam {

// Degrees are for people (config keys, reports), radians for the maths. The multiply-then-divide
// order is the one every call site used, so results stay bit for bit as they were.
constexpr double degrees(double radians) { return radians * 180.0 / M_PI; }
constexpr double radians(double degrees) { return degrees * M_PI / 180.0; }

// The angle of a rotation, degrees; through AngleAxis (a quaternion's atan2), exact also for
// tiny angles where acos((trace - 1) / 2) loses every digit.
inline double rotationAngleDeg(const Eigen::Matrix3d& R) {
  return degrees(Eigen::AngleAxisd(R).angle());
}

}  // namespace ply_slam
