#pragma once

#include <memory>

#include "ply_slam/common/config.h"
#include "ply_slam/map/map.h"
#include "ply_slam/mapping/landmark_fuser.h"
#include "ply_slam/mapping/local_bundle_adjuster.h"

namespace ply_slam {

// The mapping side: joins each new keyframe's landmarks with its neighbours', refines the map
// around it (local bundle adjustment) and retires landmarks that lost their observations. Loop
// closure and dense maps join here.
class Mapper {
 public:
  Mapper(const SystemConfig& config, Map& map)
      : config_(config), map_(map), fuser_(config), bundle_adjuster_(config) {}

  LocalBundleAdjustmentStats insertKeyFrame(const std::shared_ptr<KeyFrame>& keyframe);

 private:
  KeyFrame* spanningTreeParent(const KeyFrame& keyframe) const;

  const SystemConfig config_;
  Map& map_;
  LandmarkFuser fuser_;
  LocalBundleAdjuster bundle_adjuster_;
};

}  // namespace ply_slam
