#pragma once

#include <Eigen/Geometry>
#include <cstddef>
#include <vector>

#include "ply_slam/common/pinhole_camera.h"
#include "ply_slam/loop/loop_options.h"

namespace ply_slam {

// One putative feature match between a loop's query and candidate keyframes: the point in each
// camera frame (back-projected with that keyframe's depth) and its two observations
// (undistorted pixels).
struct PutativeMatch {
  Eigen::Vector3d p_query = Eigen::Vector3d::Zero();
  Eigen::Vector3d p_candidate = Eigen::Vector3d::Zero();
  Eigen::Vector2d uv_query = Eigen::Vector2d::Zero();
  Eigen::Vector2d uv_candidate = Eigen::Vector2d::Zero();
};

struct GeometricCheckResult {
  bool accepted = false;
  // Maps candidate-camera points into the query camera: p_query = T * p_candidate.
  Eigen::Isometry3d T_query_candidate = Eigen::Isometry3d::Identity();
  std::vector<size_t> inliers;   // indices of matches that are 3D inliers and reproject in both
  int inliers_3d = 0;            // matches within the 3D bound of the refined pose
  int reprojection_inliers = 0;  // matches (of all) reprojecting within the px bound in both
};

// Geometric verification of a loop candidate: (a) RANSAC over minimal samples of 3 matches,
// each hypothesis the closed-form rigid alignment (alignRigid, Umeyama without scale); a match
// is a 3D inlier when |p_q - T p_c| < inlierDistance(z_q, z_c); the best hypothesis is re-fit on
// its inliers until the set stops changing. (b) With that pose, each match's point is
// reprojected into the other image. Accepted when inliers_3d >= min_inliers_3d,
// reprojection_inliers >= min_reprojection_inliers and the pose is a revisit (within
// max_revisit_distance_m and max_revisit_angle_deg). Deterministic: the RNG is seeded with
// options.ransac_seed.
GeometricCheckResult checkLoopGeometry(const std::vector<PutativeMatch>& matches,
                                       const PinholeCamera& camera, const LoopOptions& options);

// The 3D inlier bound of a match whose point lies at depth z_q resp. z_c in the two cameras:
// k sqrt(sigma_Z^2(z_q) + sigma_Z^2(z_c)) (the two depth errors are independent and dominate
// the 3D error), at least options.min_inlier_distance.
double inlierDistance(double z_q, double z_c, const LoopOptions& options);

}  // namespace ply_slam
