#pragma once

#include <memory>
#include <set>
#include <vector>

#include "ply_slam/common/config.h"
#include "ply_slam/map/map.h"
#include "ply_slam/mapping/key_frame_culler.h"
#include "ply_slam/mapping/landmark_fuser.h"
#include "ply_slam/mapping/local_bundle_adjuster.h"
#include "ply_slam/mapping/map_point_culler.h"

namespace ply_slam {

// What the mapping side did with one keyframe.
struct KeyFrameInsertionStats {
  LocalBundleAdjustmentStats bundle_adjustment;
  // Keyframes erased as redundant: whatever keeps keyframes by id (the place database) must
  // drop them too.
  std::vector<long> culled_keyframes;
  int culled_points = 0;  // points retired as unreliable or unconfirmed (not merges)
};

// The mapping side: joins each new keyframe's landmarks with its neighbours', refines the map
// around it (local bundle adjustment), then retires landmarks that proved unreliable and
// keyframes that became redundant. Loop closure and dense maps join here.
class Mapper {
 public:
  Mapper(const SystemConfig& config, Map& map)
      : config_(config), map_(map), fuser_(config), bundle_adjuster_(config) {}

  // `keep`: keyframe ids culling must leave (the tracker's reference keyframe, a loop being
  // closed); the new keyframe and the first one are always kept.
  KeyFrameInsertionStats insertKeyFrame(const std::shared_ptr<KeyFrame>& keyframe,
                                        const std::set<long>& keep = {});

 private:
  KeyFrame* spanningTreeParent(const KeyFrame& keyframe) const;

  const SystemConfig config_;
  Map& map_;
  LandmarkFuser fuser_;
  LocalBundleAdjuster bundle_adjuster_;
  MapPointCuller point_culler_;
  KeyFrameCuller keyframe_culler_;
};

}  // namespace ply_slam
