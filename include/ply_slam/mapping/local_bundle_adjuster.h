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
  int outliers_removed = 0;
};

// Ceres bundle adjustment around a new keyframe: its covisible keyframes' poses and every
// landmark they see, with reprojection + depth residuals (the same as pose optimisation),
// Huber, and removal of the observations that remain outliers.
class LocalBundleAdjuster {
 public:
  LocalBundleAdjuster(const SystemConfig& config) : config_(config) {}

  LocalBundleAdjustmentStats adjust(Map& map, KeyFrame& keyframe) const;
  // Every keyframe and landmark (global bundle adjustment, after a loop), the first keyframe
  // fixed.
  LocalBundleAdjustmentStats adjustAll(Map& map, int max_iterations) const;

 private:
  // Adjusts the keyframes' poses and every landmark they see; other keyframes that see those
  // landmarks, and the first keyframe, stay fixed.
  LocalBundleAdjustmentStats adjustWindow(Map& map, const std::vector<KeyFrame*>& keyframes,
                                          int max_iterations) const;

  const SystemConfig config_;
};

}  // namespace ply_slam
