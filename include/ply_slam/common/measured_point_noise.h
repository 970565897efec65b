#pragma once

#include <Eigen/Core>

#include "ply_slam/common/pinhole_camera.h"

namespace ply_slam {

// Noise of a 3D point an RGB-D camera measures: its pixel with sigma px in u and v, its depth
// with the sensor's depth noise. P = ((u - cx) Z / fx, (v - cy) Z / fy, Z), so
// J = dP/d(u, v, Z) = [[Z/fx, 0, X/Z], [0, Z/fy, Y/Z], [0, 0, 1]] and
// Σ = J diag(σ², σ², σ_Z²) Jᵀ (PAPER.md §3.1 step 3). The line fit uses Σ, the dynamic check
// (§3.2) its variance along an edge.
class MeasuredPointNoise {
 public:
  MeasuredPointNoise(const PinholeCamera& camera, double pixel_sigma);

  // Σ of the camera-frame point p (p.z() > 0).
  Eigen::Matrix3d covariance(const Eigen::Vector3d& p) const;
  // dᵀ Σ d for a unit direction d: depth noise along p's ray, pixel noise across it. Written
  // out rather than through covariance(): the dynamic check asks it for every Delaunay edge.
  double varianceAlong(const Eigen::Vector3d& p, const Eigen::Vector3d& d) const;

 private:
  double fx_, fy_;
  DepthNoiseModel depth_noise_;
  double pixel_sigma_;
};

}  // namespace ply_slam
