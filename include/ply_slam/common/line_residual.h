#pragma once

#include <ceres/rotation.h>

#include <Eigen/Core>

#include "ply_slam/common/pinhole_camera.h"
#include "ply_slam/common/point_residual.h"

namespace ply_slam {

// Whitened residual of one line observation (PAPER.md §3), shared by pose optimisation and
// bundle adjustment: the signed distances (px) of the 3D segment's two ends, projected, to the
// observed 2D line, times `scale` (1 / sigma, and sqrt(F) in pose optimisation).
// pose = [angle-axis (3), translation (3)] of T_cw; start, end = world points (3 each).
struct LineResidual {
  Eigen::Vector3d line = Eigen::Vector3d::Zero();  // l . (u, v, 1) = signed distance in px
  double scale = 1.0;

  template <typename T>
  void evaluate(const PinholeCamera& cam, const T* pose, const T* start, const T* end,
                T* residual) const {
    residual[0] = endpoint(cam, pose, start);
    residual[1] = endpoint(cam, pose, end);
  }

 private:
  template <typename T>
  T endpoint(const PinholeCamera& cam, const T* pose, const T* world) const {
    T p[3];
    ceres::AngleAxisRotatePoint(pose, world, p);
    p[0] += pose[3];
    p[1] += pose[4];
    p[2] += pose[5];
    // Behind the camera: a large constant without gradient (as PointResidual).
    if (p[2] < T(PointResidual::kMinDepth)) return T(PointResidual::kBehindCameraResidual);
    const T u = T(cam.fx) * p[0] / p[2] + T(cam.cx), v = T(cam.fy) * p[1] / p[2] + T(cam.cy);
    return (T(line.x()) * u + T(line.y()) * v + T(line.z())) * T(scale);
  }
};

}  // namespace ply_slam
