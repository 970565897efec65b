#pragma once

#include <Eigen/Geometry>
#include <vector>

namespace ply_slam {

// The rotation nearest to m in the Frobenius norm (SVD; a reflection is never returned).
Eigen::Matrix3d nearestRotation(const Eigen::Matrix3d& m);

// Closed-form rigid alignment (Horn / Umeyama, no scale) minimising sum |gt - T est|^2.
Eigen::Isometry3d alignRigid(const std::vector<Eigen::Vector3d>& est,
                             const std::vector<Eigen::Vector3d>& gt);

}  // namespace ply_slam
