#include "ply_slam/mapping/mapper.h"

namespace ply_slam {

KeyFrame* Mapper::spanningTreeParent(const KeyFrame& keyframe) const {
  const std::vector<KeyFrame*> best = keyframe.bestCovisible(1);
  if (!best.empty()) return best.front();
  // A keyframe that shares nothing (after a loss) hangs off the one added before it.
  const auto keyframes = map_.keyFrames();
  return keyframes.size() >= 2 ? keyframes[keyframes.size() - 2].get() : nullptr;
}

LocalBundleAdjustmentStats Mapper::insertKeyFrame(const std::shared_ptr<KeyFrame>& keyframe) {
  if (keyframe->id == 0) return {};  // nothing to adjust against yet
  fuser_.fuse(map_, *keyframe, keyframe->bestCovisible(config_.tracking.local_map_keyframes));
  keyframe->parent = spanningTreeParent(*keyframe);
  const LocalBundleAdjustmentStats stats = bundle_adjuster_.adjust(map_, *keyframe);
  map_.removeBadPoints();
  return stats;
}

}  // namespace ply_slam
