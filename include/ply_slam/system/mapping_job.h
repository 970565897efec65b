#pragma once

#include <cstdint>
#include <memory>
#include <opencv2/core.hpp>
#include <vector>

#include "ply_slam/io/rgbd_images.h"
#include "ply_slam/map/key_frame.h"
#include "ply_slam/map/key_frame_packet.h"
#include "ply_slam/map/map.h"
#include "ply_slam/map/tracker_report.h"
#include "ply_slam/mapping/loop_corrector.h"

namespace ply_slam {

// A keyframe the tracker made, with what the mapping side needs of its frame (none: write back
// a global bundle adjustment that ended after the last keyframe).
struct MappingJob {
  std::shared_ptr<KeyFrame> keyframe;
  RgbdImages images;
  KeyFrameSegmentation segmentation;  // the instances as judged (segmentationOf)
  // Split modes: what the tracker did to its copy of the map since the keyframe before, and
  // `keyframe` is the mapping side's own (KeyFrame::unlinkedCopy).
  TrackerReport report;
  // Split modes: how many updates the tracker's copy had followed when the report began: the
  // merges of later ones it may not know (LandmarkCreator::replay's `merged`).
  long followed_updates = 0;
  // Split modes: the keyframe the tracker handed over before this one (-1: none, or erased) and
  // its pose (T_cw) in the tracker's copy when it made this one: the pose and the report are
  // relative to it. The mapping side moves them as it has that keyframe now (a local BA or a
  // loop the tracker had not followed yet; MappingSide::moveSinceTracked).
  long made_after = -1;
  Eigen::Isometry3d made_after_T_cw = Eigen::Isometry3d::Identity();
  // The tracker's reference keyframe when it handed the job over: culling leaves it (the
  // mapping side of another process has no other way to know it).
  long reference_keyframe = -1;
  // The checksum of the map file the tracker's map started from (MapFileContents::checksum; 0:
  // an empty map): the mapping side must have started from the same (MappingSide::checkJob).
  uint64_t loaded_map = 0;

  // The same job owning copies of its images: the mapping side may run later on another
  // thread while the caller reuses its buffers, and the keyframe packet keeps these copies.
  MappingJob detached() const {
    MappingJob job = *this;
    job.images.rgb = images.rgb.clone();
    job.images.depth = images.depth.clone();
    job.segmentation.label_image = segmentation.label_image.clone();
    job.segmentation.dynamic_mask = segmentation.dynamic_mask.clone();
    return job;
  }
};

// What one side apart gives the other when that one starts anew: a tracker to a mapping side
// that restarted or missed jobs (System::handOverMap, MappingSide::takeOver: the copy holds all
// its jobs so far), a mapping side to a tracker that restarted (MappingSide::handOverMap,
// System::takeOverMap).
struct MapHandover {
  std::vector<uint8_t> map_file;  // the map as a map file (MapFileWriter::encode)
  long updates_followed = 0;      // updates made and followed: the other side counts on from it
  uint64_t loaded_map = 0;        // the map file the tracker started from (MappingJob::loaded_map)
  Map::Ids next_ids;              // the map's: its erased landmarks' ids are not given again
};

// What the mapping side made of one keyframe, for whoever keeps a copy of the map (dense maps,
// mapping_node): the packet first, then what changed.
struct MappedKeyFrame {
  // Null only for a global bundle adjustment written back after the last keyframe: then
  // map_update alone (the whole map).
  std::shared_ptr<const KeyFramePacket> packet;
  // Set when the keyframe closed a loop: the correction and its counts.
  std::shared_ptr<const LoopCorrection> loop_correction;
  // What the mapping side changed (local BA's window, culled keyframes, or after a loop the
  // whole map).
  std::shared_ptr<const MapUpdate> map_update;
  int culled_points = 0;  // retired as unreliable or unconfirmed (the keyframes: map_update)
  // Fusion with the neighbours: landmarks merged into another (duplicates of one point), and
  // observations gained by keypoints that had no landmark.
  int merged_points = 0, fused_observations = 0;
  double ms = 0.0;  // the mapping side's time for it
};

}  // namespace ply_slam
