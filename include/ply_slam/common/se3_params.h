#pragma once

#include <Eigen/Geometry>
#include <array>

namespace ply_slam {

// A rigid transform as the 6 numbers Ceres optimises: angle-axis rotation, translation.
using Se3Params = std::array<double, 6>;

Se3Params toParams(const Eigen::Isometry3d& T);
Eigen::Isometry3d fromParams(const double* params);

}  // namespace ply_slam
