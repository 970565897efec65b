#include "ply_slam/mapping/mapper.h"

namespace ply_slam {

KeyFrame* Mapper::spanningTreeParent(const KeyFrame& keyframe) const {
  const std::vector<KeyFrame*> best = keyframe.bestCovisible(1);
  if (!best.empty()) return best.front();
  // A keyframe that shares nothing (after a loss) hangs off the one added before it.
  const auto keyframes = map_.keyFrames();
  return keyframes.size() >= 2 ? keyframes[keyframes.size() - 2].get() : nullptr;
}

KeyFrameInsertionStats Mapper::insertKeyFrame(const std::shared_ptr<KeyFrame>& keyframe,
                                              const std::set<long>& keep) {
  KeyFrameInsertionStats stats;
  if (keyframe->id == 0) return stats;  // nothing to adjust against yet
  const std::vector<KeyFrame*> neighbours =
      keyframe->bestCovisible(config_.tracking.local_map_keyframes);
  fuser_.fuse(map_, *keyframe, neighbours);
  keyframe->parent = spanningTreeParent(*keyframe);
  stats.bundle_adjustment = bundle_adjuster_.adjust(map_, *keyframe);
  // Fusion and adjustment changed who sees what: the neighbourhood is taken again.
  stats.culled_points = point_culler_.cull(
      map_, *keyframe, keyframe->bestCovisible(config_.tracking.local_map_keyframes));
  stats.culled_keyframes = keyframe_culler_.cull(map_, *keyframe, keep);
  map_.removeBadPoints();
  return stats;
}

}  // namespace ply_slam
