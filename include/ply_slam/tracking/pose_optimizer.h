#pragma once

#include <Eigen/Geometry>
#include <vector>

#include "ply_slam/common/pinhole_camera.h"

namespace ply_slam {

// One landmark seen in the current frame.
struct PointObservation {
  Eigen::Vector3d world;     // landmark position, world frame (m)
  Eigen::Vector2d pixel;     // undistorted observation (px)
  double pixel_sigma = 1.0;  // px; grows with the pyramid level
  double depth = 0.0;        // measured depth (m), 0 when the pixel has none
  double depth_sigma = 0.0;  // m, from the sensor noise model
};

struct PoseOptimizerParams {
  double chi2_pixel = 5.991;  // 2-DoF 95 %: reprojection outlier above
  double chi2_depth = 7.815;  // 3-DoF 95 %: with the depth residual
  int rounds = 4;             // solve, re-classify outliers, repeat
  int max_iterations = 10;    // per round
};

// Camera pose from point correspondences with Ceres: whitened reprojection error (plus a
// depth residual where the pixel has depth), Huber kernel, and rounds that re-classify
// every observation as inlier or outlier against the chi-square bounds.
class PoseOptimizer {
 public:
  PoseOptimizer(const PinholeCamera& camera, const PoseOptimizerParams& params);

  // Refines T_cw in place; inlier[i] tells whether observation i fits. Returns inliers.
  int optimize(const std::vector<PointObservation>& observations, Eigen::Isometry3d& T_cw,
               std::vector<bool>& inlier) const;

 private:
  double squaredError(const PointObservation& o, const Eigen::Isometry3d& T_cw) const;

  PinholeCamera camera_;
  PoseOptimizerParams params_;
};

}  // namespace ply_slam
