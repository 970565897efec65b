#pragma once

#include <map>
#include <memory>
#include <set>
#include <stdexcept>

#include "ply_slam/common/config.h"
#include "ply_slam/common/stamped_pose.h"
#include "ply_slam/dynamic/dynamic_rejector.h"
#include "ply_slam/features/line_extractor.h"
#include "ply_slam/features/line_fitter.h"
#include "ply_slam/features/orb_extractor.h"
#include "ply_slam/io/tum_sequence.h"
#include "ply_slam/map/anchored_trajectory.h"
#include "ply_slam/map/key_frame_packet.h"
#include "ply_slam/map/map.h"
#include "ply_slam/map/map_file_contents.h"
#include "ply_slam/mapping/mapper.h"
#include "ply_slam/semantic/instance.h"
#include "ply_slam/semantic/instance_memory.h"
#include "ply_slam/tracking/tracker.h"

namespace ply_slam {

// Milliseconds spent on one frame, per stage.
struct FrameTiming {
  double features_ms = 0.0;  // grey conversion, ORB, undistortion, depth lookup
  double lines_ms = 0.0;     // line detection (beside ORB on a second thread), then LBD and 3D
                             // fitting side by side (0 when disabled); not a share of total_ms
  double tracking_ms = 0.0;  // matching, pose optimisation, keyframe insertion
  double total_ms = 0.0;     // features + lines + tracking: what the frame costs the tracking side
  double mapping_ms = 0.0;   // local bundle adjustment after a new keyframe (mapping side)
};

// One extracted point feature and what became of it (for the tracking image and reports).
struct FeatureMark {
  cv::Point2f pixel;  // raw image
  FeatureFate fate = FeatureFate::kKept;
  bool inlier = false;  // kept, matched to a landmark and an inlier of the pose optimisation
};

struct FrameResult {
  long frame_id = 0;
  double stamp = 0.0;
  TrackingResult tracking;
  FrameTiming timing;
  size_t dynamic_features = 0;  // dropped because they lay on a moving object
  size_t dynamic_lines = 0;     // lines dropped: an endpoint on a dynamic instance
  std::vector<FeatureMark> features;
  std::vector<Instance> instances;   // as judged: the segmenter's and those carried on for it
  std::set<int> dynamic_instances;   // ids of the instances judged moving
  std::set<int> measured_instances;  // those of them this frame's own evidence found moving
  cv::Mat dynamic_mask;              // their dilated union (8UC1), empty when none
  // The mapping side's culling after this frame's keyframe: points retired (the keyframes erased
  // are in map_update).
  int culled_points = 0;
  // Set when the frame became a keyframe: what the mapping side (dense maps, mapping_node) gets.
  std::shared_ptr<const KeyFramePacket> keyframe_packet;
  // Set when the keyframe closed a loop: the correction and its counts.
  std::shared_ptr<const LoopCorrection> loop_correction;
  // Set with a keyframe: what the mapping side changed (local BA's window, culled keyframes, or
  // after a loop the whole map) for whoever keeps a copy of the map (mapping_node).
  std::shared_ptr<const MapUpdate> map_update;
};

// A frame the system cannot use (empty, wrong encoding or size, stamp not increasing).
// The system's state is unchanged when this is thrown.
class InvalidFrame : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

// The whole pipeline in one process, frame by frame. Used by the offline tools and tests.
class System {
 public:
  explicit System(const SystemConfig& config);

  // rgb: 8UC3 BGR; depth: 32FC1 metres (0 or NaN = invalid); both of the configured size.
  // Dynamic features are left out as config.dynamic.mode says (PAPER.md §3.2).
  FrameResult process(const RgbdImages& images, const std::vector<Instance>& instances = {});

  // Tracked frames, each placed relative to its reference keyframe as the map has that keyframe
  // now: bundle adjustment and loop closure move the past with the map.
  Trajectory cameraTrajectory() const;
  Trajectory keyFrameTrajectory() const;
  // Every keyframe of the map as it is now, without images (for a mapper that restarted).
  std::vector<KeyFramePacket> sparseKeyFramePackets() const;
  // Loop closure's counts; null without loop.enabled.
  const LoopClosureCounts* loopCounts() const { return mapper_.loopCounts(); }
  const Map& map() const { return map_; }

  // The map file a saved map is in, inside the folder saveMap and loadMap take.
  static constexpr const char* kMapFileName = "map.plymap";
  // Writes the map (keyframes with features, poses, landmarks, covisibility, spanning tree,
  // place-recognition data) into folder/map.plymap (MapFileWriter); the folder is created.
  // Throws std::runtime_error naming the file.
  void saveMap(const std::string& folder) const;
  // Before the first frame: takes the map saved in `folder`. Tracking starts lost and
  // relocalises in it (place-recognition candidates and PnP), so no pose is reported before;
  // frame and keyframe ids continue after the map's. `localisation_only`: no keyframes nor
  // landmarks are added; false: the map is extended. Throws std::runtime_error naming the file
  // and the fault (missing, truncated, corrupted, another version, camera, pyramid or
  // vocabulary), the system unchanged; std::logic_error after the first frame.
  void loadMap(const std::string& folder, bool localisation_only = true);
  // The camera, pyramid and vocabularies a map file made by this system records.
  MapFileSetup mapFileSetup() const;
  const SystemConfig& config() const { return config_; }

 private:
  void validate(const RgbdImages& images) const;
  // Judges the frame's features (PAPER.md §3.2), drops the dynamic ones, records the fates.
  void rejectDynamic(FrameFeatures& features, double stamp, const std::vector<Instance>& instances,
                     FrameResult& result);
  static void markInliers(const Frame& frame, std::vector<FeatureMark>& marks);
  // The mapping side, in line so that offline runs are reproducible: map upkeep, the packet,
  // then the loop query (which needs the packet's images).
  void map(const RgbdImages& images, const std::vector<Instance>& judged, FrameResult& result);
  // Frames anchored on keyframes the mapping side erased move to live ones, where they are.
  void reanchorTrackedFrames(const std::vector<long>& erased);
  AnchoredTrajectory::KeyFramePoses anchorPoses() const;

  SystemConfig config_;
  OrbExtractor extractor_;
  std::unique_ptr<LineExtractor> line_extractor_;  // null when lines are disabled
  std::unique_ptr<LineFitter> line_fitter_;
  DynamicRejector rejector_;
  InstanceMemory memory_;
  Map map_;
  Tracker tracker_;
  Mapper mapper_;
  long next_frame_id_ = 0;
  double last_stamp_ = -1.0;
  // Tracked frames, each relative to the tracker's reference keyframe of its time; the
  // keyframes they hang from (culled ones are replaced at once, see reanchorTrackedFrames).
  AnchoredTrajectory tracked_;
  std::map<long, std::shared_ptr<const KeyFrame>> anchors_;
};

}  // namespace ply_slam
