#pragma once

#include <memory>

#include "ply_slam/common/config.h"
#include "ply_slam/map/map.h"
#include "ply_slam/mapping/local_bundle_adjuster.h"

namespace ply_slam {

// The mapping side: refines the map around each new keyframe (local bundle adjustment) and
// retires landmarks that lost their observations. Loop closure and dense maps join here.
class Mapper {
 public:
  Mapper(const SystemConfig& config, Map& map) : map_(map), bundle_adjuster_(config) {}

  LocalBundleAdjustmentStats insertKeyFrame(const std::shared_ptr<KeyFrame>& keyframe);

 private:
  Map& map_;
  LocalBundleAdjuster bundle_adjuster_;
};

}  // namespace ply_slam
