#pragma once

#include <memory>
#include <vector>

#include "ply_slam/common/config.h"
#include "ply_slam/map/map.h"

namespace ply_slam {

// Finds the landmarks of neighbouring keyframes in a new keyframe and the other way round:
// a keypoint without a landmark gains an observation, and two landmarks found on one
// keypoint are merged. Without this every keyframe would map the same corners afresh and
// bundle adjustment would have no landmark seen twice to work with.
class LandmarkFuser {
 public:
  explicit LandmarkFuser(const SystemConfig& config);

  // Returns the number of observations added plus landmarks merged.
  int fuse(Map& map, KeyFrame& keyframe, const std::vector<KeyFrame*>& neighbours) const;

 private:
  int fuseInto(Map& map, KeyFrame& target,
               const std::vector<std::shared_ptr<MapPoint>>& points) const;

  const SystemConfig config_;
  double log_scale_;
};

}  // namespace ply_slam
