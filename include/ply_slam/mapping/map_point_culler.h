#pragma once

#include <memory>
#include <vector>

#include "ply_slam/map/map.h"

namespace ply_slam {

// When a point landmark is retired (ORB-SLAM's MapPointCulling, with this project's guard).
struct MapPointCullerOptions {
  // ORB-SLAM: a point matched in fewer than a quarter of the frames it was in view of is
  // unreliable (a reflection, a moving object, a bad descriptor).
  double min_found_ratio = 0.25;
  // Ours (the tracker's rule before): a ratio over fewer views says little.
  int min_visible = 10;
  // ORB-SLAM: a new point is judged by its observers from this many keyframes after its own on.
  int probation_keyframes = 2;
  // ORB-SLAM2 retires a point seen by <= 2 (monocular) or <= 3 (stereo, RGB-D) observations
  // then, but counts an RGB-D view twice: both mean "fewer than two keyframes".
  int min_keyframe_observers = 2;
};

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
