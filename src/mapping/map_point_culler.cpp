#include "ply_slam/mapping/map_point_culler.h"

namespace ply_slam {

int MapPointCuller::cull(Map& map, const KeyFrame& newest,
                         const std::vector<KeyFrame*>& neighbours) {
  for (const auto& p : newest.map_points)
    if (p && !p->bad && p->first_keyframe_id == newest.id) recent_.push_back(p);
  int erased = cullRecent(map, newest);
  std::vector<const KeyFrame*> local(neighbours.begin(), neighbours.end());
  local.push_back(&newest);
  for (const KeyFrame* kf : local) {
    // A copy: erasing unlinks the point from kf->map_points.
    const std::vector<std::shared_ptr<MapPoint>> points = kf->map_points;
    for (const auto& p : points) {
      if (!p || p->bad || !unreliable(*p)) continue;
      map.erasePoint(p);
      ++erased;
    }
  }
  return erased;
}

bool MapPointCuller::unreliable(const MapPoint& point) const {
  return point.visible >= options_.min_visible && point.foundRatio() < options_.min_found_ratio;
}

int MapPointCuller::cullRecent(Map& map, const KeyFrame& newest) {
  int erased = 0;
  std::vector<std::shared_ptr<MapPoint>> still_recent;
  for (const auto& p : recent_) {
    if (p->bad) continue;
    const long age = newest.id - p->first_keyframe_id;  // keyframes since its own
    if (unreliable(*p) || (age >= options_.probation_keyframes &&
                           p->observations() < options_.min_keyframe_observers)) {
      map.erasePoint(p);
      ++erased;
    } else if (age <= options_.probation_keyframes) {
      still_recent.push_back(p);
    }
  }
  recent_ = std::move(still_recent);
  return erased;
}

}  // namespace ply_slam
