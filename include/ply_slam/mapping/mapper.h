#pragma once

#include <memory>
#include <optional>

#include "ply_slam/common/config.h"
#include "ply_slam/map/map.h"
#include "ply_slam/mapping/landmark_fuser.h"
#include "ply_slam/mapping/local_bundle_adjuster.h"
#include "ply_slam/mapping/loop_closer.h"

namespace ply_slam {

// The mapping side: joins each new keyframe's landmarks with its neighbours', refines the map
// around it (local bundle adjustment), retires landmarks that lost their observations and,
// with loop.enabled, recognises places and closes loops.
class Mapper {
 public:
  // Loads the vocabularies when loop.enabled (throws std::runtime_error naming a bad file).
  Mapper(const SystemConfig& config, Map& map);

  LocalBundleAdjustmentStats insertKeyFrame(const std::shared_ptr<KeyFrame>& keyframe);
  // After insertKeyFrame, with the keyframe's packet (its images and instances): the place
  // database and a loop query; returns the correction when a loop was closed. Nothing without
  // loop.enabled.
  std::optional<LoopCorrection> closeLoop(KeyFrame& keyframe, const KeyFramePacket& packet);
  // Relocalisation candidates (keyframe ids, most similar first); empty without loop.enabled.
  std::vector<long> recognise(const cv::Mat& orb_descriptors, size_t max_results) const;
  bool recognisesPlaces() const { return loop_closer_ != nullptr; }
  // Null without loop.enabled.
  const LoopClosureCounts* loopCounts() const {
    return loop_closer_ ? &loop_closer_->counts() : nullptr;
  }

 private:
  // The whole map as a MapUpdate (after a loop: what the other side and the dense maps need).
  MapUpdate wholeMap() const;
  KeyFrame* spanningTreeParent(const KeyFrame& keyframe) const;

  const SystemConfig config_;
  Map& map_;
  LandmarkFuser fuser_;
  LocalBundleAdjuster bundle_adjuster_;
  std::unique_ptr<LoopCloser> loop_closer_;
};

}  // namespace ply_slam
