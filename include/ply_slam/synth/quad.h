#pragma once

#include <Eigen/Core>

#include "ply_slam/synth/surface_material.h"

namespace ply_slam {

// The renderer's only primitive: a planar rectangle origin + a u + b v, (a, b) in [0, 1]^2.
// Walls, boxes, pictures and walkers are all made of quads; the borders where two differently
// shaded quads meet are the scene's line segments.
struct Quad {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();   // world frame, metres
  Eigen::Vector3d axis_u = Eigen::Vector3d::UnitX();  // full edge vectors, orthogonal
  Eigen::Vector3d axis_v = Eigen::Vector3d::UnitY();
  SurfaceMaterial material;
  int instance = 0;  // masks: 0 = unlabelled static scene, else a walker or labelled object

  Eigen::Vector3d corner(int k) const;  // 0: origin, 1: +u, 2: +u+v, 3: +v
};

}  // namespace ply_slam
