#pragma once

#include <atomic>
#include <functional>
#include <memory>

#include "ply_slam/common/pinhole_camera.h"
#include "ply_slam/map/key_frame.h"
#include "ply_slam/map/map.h"
#include "ply_slam/mapping/bundle_window.h"
#include "ply_slam/mapping/local_mapping_options.h"

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
//
// In three steps, so that the map's lock is held only to read and to write: gather* and apply
// with Map::updateMutex() held, solve without. adjust does all three for a caller that
// holds the lock throughout.
class LocalBundleAdjuster {
 public:
  LocalBundleAdjuster(const PinholeCamera& camera, const LocalMappingOptions& options)
      : camera_(camera), options_(options) {}

  LocalBundleAdjustmentStats adjust(Map& map, KeyFrame& keyframe) const;

  // The window around `keyframe`: it and its best covisible keyframes.
  BundleWindow gatherLocal(KeyFrame& keyframe) const;
  // Every keyframe and landmark (the global bundle adjustment after a loop), the first
  // keyframe fixed. `between`, when given, is called after each keyframe's landmarks and each
  // landmark's observations were read, and may let go of the map's lock meanwhile: keyframes
  // made while it was free stay out of the window.
  BundleWindow gatherAll(const Map& map, int max_iterations,
                         const std::function<void()>& between = {}) const;
  // Changes only the window's numbers. Returns false, the numbers then half-solved, when
  // `abandon` turned true meanwhile.
  bool solve(BundleWindow& window, const std::atomic<bool>* abandon = nullptr) const;
  // Unlinks the observations that remain outliers and writes the poses and positions back.
  // What changed in the map since gathering is respected: an observation no longer linked is
  // left alone, a landmark turned bad keeps its place.
  LocalBundleAdjustmentStats apply(Map& map, const BundleWindow& window) const;

 private:
  // The keyframes' poses and every landmark they see, the first keyframe fixed; other keyframes
  // that see those landmarks enter fixed when `outsiders_fixed`, else their observations stay
  // out. `between` as in gatherAll.
  BundleWindow gather(const std::vector<KeyFrame*>& keyframes, int max_iterations,
                      bool outsiders_fixed, const std::function<void()>& between) const;
  double chi2Bound(const PointResidual& residual) const;

  const PinholeCamera camera_;
  const LocalMappingOptions options_;
};

}  // namespace ply_slam
