#pragma once

#include <Eigen/Geometry>
#include <array>

namespace ply_slam {

// A rigid transform as the 6 numbers Ceres optimises: angle-axis rotation, translation.
using Se3Params = std::array<double, 6>;

Se3Params toParams(const Eigen::Isometry3d& T);
Eigen::Isometry3d fromParams(const double* params);
// The rigid transform nearest T (its rotation through a normalised quaternion): composed
// transforms drift off the rotations, and Isometry3d's inverse (a transpose) feeds the drift on.
Eigen::Isometry3d nearestRigid(const Eigen::Isometry3d& T);

}  // namespace ply_slam
