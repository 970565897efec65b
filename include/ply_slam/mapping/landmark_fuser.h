#pragma once

#include <memory>
#include <vector>

#include "ply_slam/common/pinhole_camera.h"
#include "ply_slam/features/orb_options.h"
#include "ply_slam/map/map.h"
#include "ply_slam/mapping/local_mapping_options.h"

namespace ply_slam {

// What one fusion did: observations a keypoint without a landmark gained, and landmarks merged
// into another found on the same keypoint (one physical point held twice).
struct FusionCounts {
  int observations_added = 0;
  int landmarks_merged = 0;
  FusionCounts& operator+=(const FusionCounts& o) {
    observations_added += o.observations_added;
    landmarks_merged += o.landmarks_merged;
    return *this;
  }
};

// Finds the landmarks of neighbouring keyframes in a new keyframe and the other way round:
// a keypoint without a landmark gains an observation, and two landmarks found on one
// keypoint are merged. Without this every keyframe would map the same corners afresh and
// bundle adjustment would have no landmark seen twice to work with.
class LandmarkFuser {
 public:
  // `orb`: the keyframes' pyramid, to predict a landmark's level.
  LandmarkFuser(const PinholeCamera& camera, const OrbOptions& orb,
                const LocalMappingOptions& options);

  FusionCounts fuse(Map& map, KeyFrame& keyframe, const std::vector<KeyFrame*>& neighbours) const;

 private:
  FusionCounts fuseInto(Map& map, KeyFrame& target,
                        const std::vector<std::shared_ptr<MapPoint>>& points) const;

  const PinholeCamera camera_;
  const int num_levels_;
  const double log_scale_;
  const double chi2_outlier_;
  const double radius_px_;  // at level 0
  const int max_distance_;
};

}  // namespace ply_slam
