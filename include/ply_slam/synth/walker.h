#pragma once

#include <Eigen/Geometry>
#include <vector>

#include "ply_slam/synth/quad.h"

namespace ply_slam {

// A person-sized textured box walking at constant speed around a stadium-shaped loop (two
// straights joined by half circles) on the floor: smooth, always inside the room, no
// stops, so a dynamic-object filter sees steady motion.
class Walker {
 public:
  struct Path {
    Eigen::Vector2d centre = Eigen::Vector2d::Zero();  // world xy of the loop's centre
    double heading = 0.0;   // rad, direction of the straights from the world x axis
    double straight = 2.0;  // m, length of each straight
    double radius = 0.5;    // m, of the half circles
    double speed = 1.2;     // m/s along the path
    double start = 0.0;     // m along the path at t = 0
  };

  // size: depth (walking direction) x width x height. sides: the photograph of a person on
  // the four vertical faces (mapped for the front's width), top: head and shoulders.
  Walker(int instance, const Path& path, const Eigen::Vector3d& size, const SurfaceMaterial& sides,
         const SurfaceMaterial& top);

  int instance() const { return instance_; }
  const Path& path() const { return path_; }
  double pathLength() const;
  // Body pose at time t (s): origin on the floor under the body's centre, x forward, z up.
  Eigen::Isometry3d pose(double t) const;
  std::vector<Quad> quads(double t) const;

 private:
  int instance_;
  Path path_;
  Eigen::Vector3d size_;
  SurfaceMaterial sides_, top_;
};

}  // namespace ply_slam
