#pragma once

#include <unordered_map>
#include <vector>

#include "ply_slam/common/pinhole_camera.h"
#include "ply_slam/map/key_frame.h"
#include "ply_slam/mapping/bundle_window.h"

namespace ply_slam {

// Fills a BundleWindow from the map, piece by piece, in a fixed order (the same map gives the
// same window). Each call reads the map: the caller holds Map::updateMutex() during it, and may
// let it go between calls (the global bundle adjustment does, so that the tracker does not
// wait for the whole map to be copied).
class BundleWindowGatherer {
 public:
  // `fixed_observers`: keyframes outside the window that see its landmarks enter with fixed
  // poses; false: their observations stay out (keyframes the tracker made after the window's
  // keyframes were taken).
  BundleWindowGatherer(const PinholeCamera& camera, int max_iterations, bool fixed_observers);

  // A pose of the window: optimised, except the first keyframe's (the gauge).
  void addKeyFrame(KeyFrame* keyframe) { addPose(keyframe, true); }
  // The landmarks the keyframe sees that the window has not got yet.
  void addLandmarksOf(const KeyFrame& keyframe);
  // Every observation of the k-th landmark; returns how many were added.
  size_t addObservationsOf(size_t k);
  size_t landmarks() const { return window_.landmarks.size(); }
  BundleWindow take() { return std::move(window_); }

 private:
  // The pose's index; npos for a keyframe outside the window when it may not enter.
  size_t addPose(KeyFrame* keyframe, bool in_window);

  const PinholeCamera camera_;
  const bool fixed_observers_;
  BundleWindow window_;
  std::unordered_map<const KeyFrame*, size_t> pose_index_;
  std::unordered_map<const MapPoint*, size_t> point_index_;
};

}  // namespace ply_slam
