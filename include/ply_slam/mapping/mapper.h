#pragma once

#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <vector>

#include "ply_slam/common/pinhole_camera.h"
#include "ply_slam/map/key_frame_packet.h"
#include "ply_slam/map/map.h"
#include "ply_slam/map/map_file_contents.h"
#include "ply_slam/mapping/global_bundle_adjustment.h"
#include "ply_slam/mapping/key_frame_culler.h"
#include "ply_slam/mapping/landmark_creator.h"
#include "ply_slam/mapping/landmark_fuser.h"
#include "ply_slam/mapping/local_bundle_adjuster.h"
#include "ply_slam/mapping/loop_closer.h"
#include "ply_slam/mapping/map_point_culler.h"
#include "ply_slam/mapping/mapper_options.h"

namespace ply_slam {

// What the mapping side did with one keyframe.
struct KeyFrameInsertionStats {
  LocalBundleAdjustmentStats bundle_adjustment;
  // Keyframes erased as redundant: whatever keeps keyframes by id (the place database) must
  // drop them too.
  std::vector<long> culled_keyframes;
  int culled_points = 0;  // points retired as unreliable or unconfirmed (not merges)
  FusionCounts fused;     // the new keyframe with its neighbours (LandmarkFuser)
  // A global bundle adjustment solved meanwhile was written back first: the whole map moved.
  bool global_ba_applied = false;
  // What local BA moved, as the step left it: the poses of its window's own keyframes and the
  // positions of the landmarks it adjusted (what culling erased left out), and the lines those
  // keyframes see (their ends move with the tracker's fits).
  MapUpdate adjusted;
};

// The global bundle adjustments after loops (GlobalBundleAdjustment).
struct GlobalBundleAdjustmentCounts {
  int started = 0;
  int applied = 0;
  int abandoned = 0;  // a newer loop came first
  double solve_ms = 0.0;
};

// The mapping side, the only code that creates, changes or erases keyframes and landmarks:
// makes keyframes and landmarks from what tracking measured (landmarkSink), joins each new
// keyframe's landmarks with its neighbours', refines the map
// around it (local bundle adjustment), retires landmarks that proved unreliable and keyframes
// that became redundant and, with loop.enabled, recognises places and closes loops.
//
// Threads: insertKeyFrame, closeLoop and wholeMap are called from one thread (the
// mapping side's, which may be the tracker's) and take map.updateMutex() themselves, step by
// step; Ceres solves, line description and the loop query with its geometric check run without
// it. recognise, places,
// addLoadedKeyFrames and landmarkSink's calls (from the tracker's thread) expect the caller to
// hold it (or no other thread to run).
class Mapper {
 public:
  // Told of each move of the whole map, with the map's lock still held, so that whoever tracks
  // in it moves along before it tracks again: T_wc(after) = correction * T_wc(before).
  using CorrectionListener = std::function<void(const Eigen::Isometry3d& correction)>;
  // Keyframe ids culling must leave (the tracker's reference keyframe); called with the lock.
  using KeepKeyFrames = std::function<std::set<long>()>;

  // Loads the vocabularies when loop.enabled (throws std::runtime_error naming a bad file).
  // `wait_for_global_ba`: closeLoop waits for the global bundle adjustment it starts and writes
  // it back (runs repeat bit for bit); false: it is solved beside the following keyframes and
  // written back at the first of them after it ended (or by applySolvedGlobalBundleAdjustment).
  Mapper(const PinholeCamera& camera, const MapperOptions& options, Map& map,
         bool wait_for_global_ba = true);

  void setCorrectionListener(CorrectionListener listener) { listener_ = std::move(listener); }
  // Where the tracker sends what it measured: new keyframes, found landmarks, line fits.
  LandmarkSink& landmarkSink() { return creator_; }
  // What a tracker working on a copy of the map reported, done to this map, with that
  // tracker's new keyframe (its unlinked copy, KeyFrame::unlinkedCopy): LandmarkCreator::replay.
  std::shared_ptr<KeyFrame> replay(const TrackerReport& report, std::shared_ptr<KeyFrame> keyframe,
                                   const LandmarkCreator::MergedPoints& merged = {}) {
    return creator_.replay(report, std::move(keyframe), merged);
  }
  // The new keyframe and the first one are always kept, and those made after the new one.
  // Culled keyframes leave the place database too.
  KeyFrameInsertionStats insertKeyFrame(const std::shared_ptr<KeyFrame>& keyframe,
                                        const KeepKeyFrames& keep = {});
  // After insertKeyFrame, with the keyframe's packet (its images and instances): the place
  // database and a loop query; returns the correction when a loop was closed. Nothing without
  // loop.enabled.
  std::optional<LoopCorrection> closeLoop(KeyFrame& keyframe, const KeyFramePacket& packet);
  // Blocks until a global bundle adjustment still running has ended (not with insertKeyFrame or
  // closeLoop running on another thread).
  void waitForGlobalBundleAdjustment() { global_ba_.wait(); }
  // Writes back a global bundle adjustment that has ended, without waiting; true when it did.
  bool applySolvedGlobalBundleAdjustment();
  // One has ended and waits to be written back (any thread may ask).
  bool globalBundleAdjustmentSolved() const { return global_ba_.hasSolved(); }
  GlobalBundleAdjustmentCounts globalBundleAdjustmentCounts() const;
  // Relocalisation candidates (keyframe ids, most similar first); empty without loop.enabled.
  std::vector<long> recognise(const cv::Mat& orb_descriptors, size_t max_results) const;
  // The whole map as a MapUpdate (whole_map set): after a loop, what copies of the map need.
  MapUpdate wholeMap() const;
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
  // With the lock held: writes back a global bundle adjustment that has ended and tells the
  // listener how the newest keyframe moved; that move, or nothing when none had ended.
  std::optional<Eigen::Isometry3d> writeBackSolvedGlobal();
  void tell(const Eigen::Isometry3d& correction) const;

  const MapperOptions options_;
  Map& map_;
  LandmarkCreator creator_;
  LandmarkFuser fuser_;
  LocalBundleAdjuster bundle_adjuster_;
  MapPointCuller point_culler_;
  KeyFrameCuller keyframe_culler_;
  std::unique_ptr<LoopCloser> loop_closer_;
  CorrectionListener listener_;
  const bool wait_for_global_ba_;
  int global_ba_applied_ = 0;
  GlobalBundleAdjustment global_ba_;  // last: its thread stops before the rest goes
};

}  // namespace ply_slam
