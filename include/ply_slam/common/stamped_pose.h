#pragma once

#include <Eigen/Geometry>
#include <vector>

namespace ply_slam {

// A camera pose at a time stamp: T_wc maps camera coordinates into the world.
struct StampedPose {
  double stamp = 0.0;
  Eigen::Isometry3d T_wc = Eigen::Isometry3d::Identity();
};

// Poses ordered by stamp (TUM trajectory files, estimates, ground truth).
using Trajectory = std::vector<StampedPose>;

}  // namespace ply_slam
