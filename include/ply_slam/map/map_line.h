#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <opencv2/core.hpp>

namespace ply_slam {

// A static 3D line segment landmark, created at a keyframe from an accepted 3D fit
// (PAPER.md §3.1) moved into the world frame, matched by its LBD descriptor. Every later
// tracked frame that matches it with an accepted fit of its own on the same 3D line averages
// that fit in (LandmarkCreator, on the mapping side), as map points average their depth
// measurements.
struct MapLine {
  long id = 0;
  Eigen::Vector3d start = Eigen::Vector3d::Zero();  // world frame, m; the end seen at the 2D start
  Eigen::Vector3d end = Eigen::Vector3d::Zero();
  double start_weight = 0.0;  // sums of the inverse depth variances fused into start and end
  double end_weight = 0.0;
  cv::Mat descriptor;  // 1x32 CV_8U LBD
  long first_keyframe_id = 0;
  int observations = 0;  // keyframes that observe it
  int found = 0;         // frames in which it was matched as an inlier
  bool bad = false;

  // Distance (m) of p to the infinite line through start and end.
  double distanceToLine(const Eigen::Vector3d& p) const;
  // Averages a fit of this line (world frame; either way round) into start and end, each
  // weighted by the inverse variance of its depth.
  void fuse(const Eigen::Vector3d& fit_start, const Eigen::Vector3d& fit_end, double weight_start,
            double weight_end);
  // Moves the segment rigidly with the world.
  void moveBy(const Eigen::Isometry3d& move);
};

}  // namespace ply_slam
