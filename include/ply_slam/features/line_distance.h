#pragma once

#include <Eigen/Core>

namespace ply_slam {

// Signed distance (px) of the pixel (u, v) from a normalised image line l = (a, b, c) with
// a² + b² = 1 (PAPER.md §3): l . (u, v, 1). A template so that Ceres' line costs use it on Jets;
// on doubles it is Eigen's l.dot(p.homogeneous()) to the bit (the same sum, left to right).
template <typename T>
T lineDistance(const Eigen::Vector3d& l, const T& u, const T& v) {
  return T(l.x()) * u + T(l.y()) * v + T(l.z());
}

inline double lineDistance(const Eigen::Vector3d& l, const Eigen::Vector2d& p) {
  return lineDistance(l, p.x(), p.y());
}

}  // namespace ply_slam
