#pragma once

#include <Eigen/Geometry>  // homogeneous(), cross()

#include "ply_slam/features/line_distance.h"

namespace ply_slam {

// One 2D line segment of an image. Oriented by its edge's polarity: walking from start to end,
// the brighter side is on the left (image axes, y down), so one edge keeps its direction from
// frame to frame and the two sides of a thin bar stay two lines.
struct LineFeature {
  Eigen::Vector2d raw_start = Eigen::Vector2d::Zero();  // raw image pixels (as detected)
  Eigen::Vector2d raw_end = Eigen::Vector2d::Zero();
  Eigen::Vector2d start = Eigen::Vector2d::Zero();  // undistorted pixels: used by the geometry
  Eigen::Vector2d end = Eigen::Vector2d::Zero();

  double length() const { return (end - start).norm(); }
  Eigen::Vector2d direction() const { return (end - start).normalized(); }
  // Normalised homogeneous line (PAPER.md §3): l . (u, v, 1) is the signed distance in px.
  Eigen::Vector3d line() const {
    const Eigen::Vector3d l = start.homogeneous().cross(end.homogeneous());
    return l / l.head<2>().norm();
  }
  double distance(const Eigen::Vector2d& p) const { return lineDistance(line(), p); }
};

}  // namespace ply_slam
