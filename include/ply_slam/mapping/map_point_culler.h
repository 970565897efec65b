#pragma once

#include <memory>
#include <vector>

#include "ply_slam/map/map.h"
#include "ply_slam/mapping/map_point_culler_options.h"

namespace ply_slam {

// Retires point landmarks after each keyframe: any point of the new keyframe's neighbourhood
// rarely found where it should be seen, and new points that no later keyframe confirmed. The
// only place that retires points for being unreliable.
class MapPointCuller {
 public:
  explicit MapPointCuller(const MapPointCullerOptions& options = {}) : options_(options) {}

  // `newest` has just joined the map; `neighbours` are its local keyframes. Erases the
  // points found unreliable from the map; returns how many.
  int cull(Map& map, const KeyFrame& newest, const std::vector<KeyFrame*>& neighbours);
  // Found too rarely where it was in view.
  bool unreliable(const MapPoint& point) const;

 private:
  // Judges the points on probation, lets go of those past it; returns the points erased.
  int cullRecent(Map& map, const KeyFrame& newest);

  MapPointCullerOptions options_;
  std::vector<std::shared_ptr<MapPoint>> recent_;  // created by the last keyframes
};

}  // namespace ply_slam
