#include "ply_slam/mapping/key_frame_culler.h"

namespace ply_slam {

std::vector<long> KeyFrameCuller::cull(Map& map, const KeyFrame& newest,
                                       const std::set<long>& keep) const {
  std::vector<long> erased;
  for (KeyFrame* kf : newest.bestCovisible(newest.covisibility.size())) {
    // Keyframes newer than `newest` are still waiting for the mapping side (it runs behind the
    // tracker on its own thread): they are judged after their own turn.
    if (kf->id >= newest.id || keep.count(kf->id) || !redundant(*kf)) continue;
    if (const auto gone = map.eraseKeyFrame(*kf, options_.min_point_observers))
      erased.push_back(gone->id);
  }
  return erased;
}

bool KeyFrameCuller::redundant(const KeyFrame& keyframe) const {
  int points = 0, redundant_points = 0;
  for (size_t i = 0; i < keyframe.map_points.size(); ++i) {
    const auto& p = keyframe.map_points[i];
    if (!p || p->bad) continue;
    ++points;
    if (seenByOthers(keyframe, i)) ++redundant_points;
  }
  return points > 0 && redundant_points > options_.redundancy * points;
}

bool KeyFrameCuller::seenByOthers(const KeyFrame& keyframe, size_t index) const {
  const MapPoint& point = *keyframe.map_points[index];
  if (point.observations() <= options_.min_observers) return false;  // not enough others
  const int level = keyframe.features.level(index);
  int others = 0;
  for (const auto& o : point.observers) {
    if (o.keyframe == &keyframe) continue;
    if (o.keyframe->features.level(o.index) > level + options_.level_slack) continue;
    if (++others >= options_.min_observers) return true;
  }
  return false;
}

}  // namespace ply_slam
