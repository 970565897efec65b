#include "ply_slam/map/map_line.h"

#include <utility>

namespace ply_slam {

double MapLine::distanceToLine(const Eigen::Vector3d& p) const {
  const Eigen::Vector3d d = (end - start).normalized(), r = p - start;
  return (r - d * d.dot(r)).norm();
}

void MapLine::fuse(const Eigen::Vector3d& fit_start, const Eigen::Vector3d& fit_end,
                   double weight_start, double weight_end) {
  Eigen::Vector3d s = fit_start, e = fit_end;
  // Another keyframe's 2D segment may run the other way.
  if (start_weight + end_weight > 0.0 && (e - s).dot(end - start) < 0.0) {
    std::swap(s, e);
    std::swap(weight_start, weight_end);
  }
  if (weight_start <= 0.0 || weight_end <= 0.0) return;
  start = (start * start_weight + s * weight_start) / (start_weight + weight_start);
  end = (end * end_weight + e * weight_end) / (end_weight + weight_end);
  start_weight += weight_start;
  end_weight += weight_end;
}

void MapLine::moveBy(const Eigen::Isometry3d& move) {
  start = move * start;
  end = move * end;
}

}  // namespace ply_slam
