#pragma once

#include <memory>
#include <optional>
#include <set>
#include <vector>

#include "ply_slam/common/config.h"
#include "ply_slam/map/key_frame_packet.h"
#include "ply_slam/map/map.h"
#include "ply_slam/map/map_file_contents.h"
#include "ply_slam/mapping/key_frame_culler.h"
#include "ply_slam/mapping/landmark_fuser.h"
#include "ply_slam/mapping/local_bundle_adjuster.h"
#include "ply_slam/mapping/loop_closer.h"
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
// around it (local bundle adjustment), retires landmarks that proved unreliable and keyframes
// that became redundant and, with loop.enabled, recognises places and closes loops.
class Mapper {
 public:
  // Loads the vocabularies when loop.enabled (throws std::runtime_error naming a bad file).
  Mapper(const SystemConfig& config, Map& map);

  // `keep`: keyframe ids culling must leave (the tracker's reference keyframe); the new
  // keyframe and the first one are always kept. Culled keyframes leave the place database too.
  KeyFrameInsertionStats insertKeyFrame(const std::shared_ptr<KeyFrame>& keyframe,
                                        const std::set<long>& keep = {});
  // After insertKeyFrame, with the keyframe's packet (its images and instances): the place
  // database and a loop query; returns the correction when a loop was closed. Nothing without
  // loop.enabled.
  std::optional<LoopCorrection> closeLoop(KeyFrame& keyframe, const KeyFramePacket& packet);
  // Relocalisation candidates (keyframe ids, most similar first); empty without loop.enabled.
  std::vector<long> recognise(const cv::Mat& orb_descriptors, size_t max_results) const;
  // The whole map as a MapUpdate (whole_map set): after a loop, what copies of the map need.
  MapUpdate wholeMap() const;
  // What local BA around `keyframe` may have moved: the poses of its window (itself and its
  // covisible keyframes) and the landmarks they see.
  MapUpdate localUpdate(const KeyFrame& keyframe) const;
  bool recognisesPlaces() const { return loop_closer_ != nullptr; }
  // What place recognition keeps of each keyframe, for a map file (empty without loop.enabled).
  std::map<long, KeyFramePlace> places() const;
  // A loaded map's keyframes (already in the map) into the place database, from their
  // features and `places`; nothing without loop.enabled.
  void addLoadedKeyFrames(const std::map<long, KeyFramePlace>& places);
  // The vocabularies place recognition uses (empty ones without loop.enabled).
  MapVocabulary orbVocabulary() const;
  MapVocabulary lbdVocabulary() const;
  // Null without loop.enabled.
  const LoopClosureCounts* loopCounts() const {
    return loop_closer_ ? &loop_closer_->counts() : nullptr;
  }

 private:
  KeyFrame* spanningTreeParent(const KeyFrame& keyframe) const;

  const SystemConfig config_;
  Map& map_;
  LandmarkFuser fuser_;
  LocalBundleAdjuster bundle_adjuster_;
  MapPointCuller point_culler_;
  KeyFrameCuller keyframe_culler_;
  std::unique_ptr<LoopCloser> loop_closer_;
};

}  // namespace ply_slam
