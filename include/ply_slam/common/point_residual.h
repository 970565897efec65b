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

  template <typename T>
  void evaluate(const PinholeCamera& cam, const T* pose, const T* world, T* residual) const {
    T p[3];
    ceres::AngleAxisRotatePoint(pose, world, p);
    p[0] += pose[3];
    p[1] += pose[4];
    p[2] += pose[5];
    if (p[2] < T(kMinDepth)) {
      // Behind the camera: a large constant without gradient, so one bad landmark can neither
      // divide by zero nor drag the solution; the caller classifies it as an outlier.
      residual[0] = residual[1] = T(kBehindCameraResidual);
      if (hasDepth()) residual[2] = T(0.0);
      return;
    }
    residual[0] = (T(cam.fx) * p[0] / p[2] + T(cam.cx) - T(u)) / T(pixel_sigma);
    residual[1] = (T(cam.fy) * p[1] / p[2] + T(cam.cy) - T(v)) / T(pixel_sigma);
    if (hasDepth()) residual[2] = (p[2] - T(depth)) / T(depth_sigma);
  }
};

}  // namespace ply_slam
