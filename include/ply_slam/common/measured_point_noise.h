#pragma once

#include <Eigen/Core>

#include "ply_slam/common/pinhole_camera.h"

namespace ply_slam {

// Noise of a 3D point an RGB-D camera measures: its pixel with sigma px in u and v, its depth
// with the sensor's depth noise. P = ((u - cx) Z / fx, (v - cy) Z / fy, Z), so
// J = dP/d(u, v, Z) = [[Z/fx, 0, X/Z], [0, Z/fy, Y/Z], [0, 0, 1]] and
// Σ = J diag(σ², σ², σ_Z²) Jᵀ (PAPER.md §3.1 step 3). The line fit uses Σ, the dynamic check
// (§3.2) its variance along an edge.
// The depth is read where the pixel lies, so on a surface that slopes in the image
// (s = (dZ/du, dZ/dv), m/px) a pixel error also moves the depth: Z = Z0 + s·(δu, δv) + ε_Z,
// and dP/du gains (P / Z) s_u. On a corridor wall 5 m ahead and 1 m aside that is 5 cm per px,
// twenty times the depth noise of an exact sensor.
class MeasuredPointNoise {
 public:
  MeasuredPointNoise(const PinholeCamera& camera, double pixel_sigma);

  // Σ of the camera-frame point p (p.z() > 0) read where the depth image slopes by `slope`.
  Eigen::Matrix3d covariance(const Eigen::Vector3d& p,
                             const Eigen::Vector2d& slope = Eigen::Vector2d::Zero()) const;
  // dᵀ Σ d for a unit direction d: depth noise along p's ray, pixel noise across it and, through
  // the slope, along it. Written out rather than through covariance(): the dynamic check asks
  // it for every Delaunay edge.
  double varianceAlong(const Eigen::Vector3d& p, const Eigen::Vector3d& d,
                       const Eigen::Vector2d& slope = Eigen::Vector2d::Zero()) const;

 private:
  double fx_, fy_;
  DepthNoiseModel depth_noise_;
  double pixel_sigma_;
};

}  // namespace ply_slam
