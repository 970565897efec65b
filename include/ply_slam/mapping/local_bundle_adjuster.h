#pragma once

#include <memory>

#include "ply_slam/common/config.h"
#include "ply_slam/map/key_frame.h"
#include "ply_slam/map/map.h"

namespace ply_slam {

struct LocalBundleAdjustmentStats {
  int keyframes = 0;        // poses optimised
  int fixed_keyframes = 0;  // poses held fixed (they observe the local points)
  int points = 0;
  int observations = 0;
  int lines = 0;              // line landmarks
  int line_observations = 0;  // their 2D observations in the keyframes
  int outliers_removed = 0;
};

// Ceres bundle adjustment around a new keyframe: its covisible keyframes' poses and every
// landmark they see, with reprojection + depth residuals (the same as pose optimisation),
// Huber, and removal of the point observations that remain outliers. Line landmarks (issue #4)
// take part with the pose optimiser's endpoint-to-line residual in every keyframe of the
// problem that sees them (KeyFrame::lines) and their fused fit (MapLine::fuse) as a prior on
// both ends: the 2D lines place them across, the prior holds their depth and their ends along
// the line.
class LocalBundleAdjuster {
 public:
  LocalBundleAdjuster(const SystemConfig& config) : config_(config) {}

  LocalBundleAdjustmentStats adjust(Map& map, KeyFrame& keyframe) const;

 private:
  const SystemConfig config_;
};

}  // namespace ply_slam
