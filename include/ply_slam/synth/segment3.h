#pragma once

#include <Eigen/Core>

namespace ply_slam {

// A straight 3D segment in the world frame (lines.txt: the scene's ground-truth lines).
struct Segment3 {
  Eigen::Vector3d a = Eigen::Vector3d::Zero();
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
  double length() const { return (b - a).norm(); }
};

}  // namespace ply_slam
