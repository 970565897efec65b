#include "ply_slam/mapping/mapper.h"

namespace ply_slam {

LocalBundleAdjustmentStats Mapper::insertKeyFrame(const std::shared_ptr<KeyFrame>& keyframe) {
  if (keyframe->id == 0) return {};  // nothing to adjust against yet
  fuser_.fuse(map_, *keyframe, keyframe->bestCovisible(config_.tracking.local_map_keyframes));
  const LocalBundleAdjustmentStats stats = bundle_adjuster_.adjust(map_, *keyframe);
  map_.removeBadPoints();
  return stats;
}

}  // namespace ply_slam
