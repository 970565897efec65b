#include "ply_slam/map/map_point.h"

#include <algorithm>
#include <cmath>

namespace ply_slam {

bool MapPoint::seenBy(const KeyFrame* keyframe) const {
  for (const auto& o : observers)
    if (o.keyframe == keyframe) return true;
  return false;
}

int MapPoint::predictLevel(double distance, double log_scale, int num_levels) const {
  const int level = static_cast<int>(std::ceil(std::log(max_distance / distance) / log_scale));
  return std::clamp(level, 0, num_levels - 1);
}

void MapPoint::fuse(const Eigen::Vector3d& measured, double weight) {
  if (position_weight + weight <= 0.0) return;
  position = (position * position_weight + measured * weight) / (position_weight + weight);
  position_weight += weight;
}

void MapPoint::moveBy(const Eigen::Isometry3d& move) {
  position = move * position;
  normal = move.linear() * normal;
}

}  // namespace ply_slam
