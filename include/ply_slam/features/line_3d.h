#pragma once

#include <Eigen/Core>

namespace ply_slam {

// A 3D segment fitted to one 2D line segment, in the camera frame of its image.
struct Line3D {
  bool valid = false;  // accepted: inlier ratio > Th1 and length > Th2 (PAPER.md §3.1)
  Eigen::Vector3d start = Eigen::Vector3d::Zero();  // m; the end seen at the 2D start
  Eigen::Vector3d end = Eigen::Vector3d::Zero();
  int samples = 0;      // points sampled along the 2D segment (N + 1; 2 for the endpoint method)
  int valid_depth = 0;  // of them with a valid depth
  int inliers = 0;      // of them on the fitted line

  double length() const { return (end - start).norm(); }
  Eigen::Vector3d direction() const { return (end - start).normalized(); }
};

}  // namespace ply_slam
