#pragma once

#include <ceres/rotation.h>

#include "ply_slam/common/pinhole_camera.h"

namespace ply_slam {

// Whitened residual of one point observation, shared by pose optimisation and bundle
// adjustment. pose = [angle-axis (3), translation (3)] of T_cw; world = landmark (3).
// Writes 2 pixel residuals, and a metric depth residual when depth_sigma > 0.
struct PointResidual {
  static constexpr double kMinDepth = 1e-3;             // m
  static constexpr double kBehindCameraResidual = 1e3;  // whitened units

  double u = 0.0, v = 0.0;   // undistorted observation (px)
  double pixel_sigma = 1.0;  // px
  double depth = 0.0;        // m
  double depth_sigma = 0.0;  // m; 0 = no depth residual

  bool hasDepth() const { return depth > 0.0 && depth_sigma > 0.0; }

  // Whether a camera-frame point can be projected: not nearer than kMinDepth (nor behind).
  static bool inFront(const Eigen::Vector3d& p_c) { return p_c.z() >= kMinDepth; }

  // world moved into the camera by pose (p_c) and its pixel (uv): the projection of points and
  // of line endpoints. False, and uv unset, when not inFront.
  template <typename T>
  static bool project(const PinholeCamera& cam, const T* pose, const T* world, T* p_c, T* uv) {
    ceres::AngleAxisRotatePoint(pose, world, p_c);
    p_c[0] += pose[3];
    p_c[1] += pose[4];
    p_c[2] += pose[5];
    if (p_c[2] < T(kMinDepth)) return false;
    cam.project(p_c, uv);
    return true;
  }

  template <typename T>
  void evaluate(const PinholeCamera& cam, const T* pose, const T* world, T* residual) const {
    T p[3], uv[2];
    if (!project(cam, pose, world, p, uv)) {
      // Behind the camera: a large constant without gradient, so one bad landmark can neither
      // divide by zero nor drag the solution; the caller classifies it as an outlier.
      residual[0] = residual[1] = T(kBehindCameraResidual);
      if (hasDepth()) residual[2] = T(0.0);
      return;
    }
    residual[0] = (uv[0] - T(u)) / T(pixel_sigma);
    residual[1] = (uv[1] - T(v)) / T(pixel_sigma);
    if (hasDepth()) residual[2] = (p[2] - T(depth)) / T(depth_sigma);
  }
};

}  // namespace ply_slam
