#pragma once

#include <Eigen/Geometry>
#include <opencv2/core.hpp>
#include <string>
#include <utility>
#include <vector>

#include "ply_slam/common/pinhole_camera.h"
#include "ply_slam/map/map_journal.h"

namespace ply_slam {

// A point landmark as the mapping side sees it. A copy of the map that tracks in it (the
// tracker's) needs the rest too (MapPoint's fields of the same names; the visible / found counts
// are the tracker's, and merges add them up on both sides by the journal); the messages carry
// the position only.
struct LandmarkPoint {
  long id = 0;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  // world frame, m
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  double position_weight = 0.0;
};

// A 3D line landmark: world-frame segment (and MapLine's weights, as LandmarkPoint's rest).
struct LandmarkLine {
  long id = 0;
  Eigen::Vector3d start = Eigen::Vector3d::Zero();
  Eigen::Vector3d end = Eigen::Vector3d::Zero();
  double start_weight = 0.0, end_weight = 0.0;
};

// One instance of the keyframe's segmentation; its pixels are those of `label_image` equal
// to `id`.
struct PacketInstance {
  int id = 0;  // 1..65535
  std::string class_name;
  float score = 1.0f;
  bool dynamic = false;  // judged moving in this frame: its pixels are left out of the maps
};

// A keyframe's segmentation as the maps take it: one label image for every instance.
struct KeyFrameSegmentation {
  cv::Mat label_image;  // 16UC1 instance id per pixel, 0 = none; empty when not segmented
  std::vector<PacketInstance> instances;
  cv::Mat dynamic_mask;  // 8UC1, non-zero: pixels of moving things (dilated); empty = none
};

// Tracker -> mapper (DESIGN.md, "One library, two transports"): everything the mapping side
// needs about a new keyframe. Plain data, mirrored 1:1 by msg/KeyFrame.msg.
struct KeyFramePacket {
  long id = 0;        // keyframe id
  long frame_id = 0;  // frame number in the sequence
  double stamp = 0.0;
  Eigen::Isometry3d T_wc = Eigen::Isometry3d::Identity();  // camera -> world
  PinholeCamera camera;                                    // the images' intrinsics
  // Features (undistorted pixels), one row of `descriptors` each; landmark id per keypoint or -1.
  std::vector<Eigen::Vector2d> keypoints;
  std::vector<float> keypoint_depth;  // m, 0 = none
  std::vector<int> keypoint_level;
  cv::Mat descriptors;  // N x 32 CV_8U
  std::vector<long> keypoint_landmark;
  std::vector<LandmarkPoint> points;  // landmarks this keyframe observes
  std::vector<LandmarkLine> lines;    // line landmarks this keyframe observes
  // What the dense map needs: the images (raw, as from the camera) and the segmentation.
  cv::Mat rgb;          // 8UC3 BGR
  cv::Mat depth;        // 32FC1 m, 0 = invalid
  cv::Mat label_image;  // 16UC1 instance id per pixel, 0 = none; empty when not segmented
  std::vector<PacketInstance> instances;
  cv::Mat dynamic_mask;  // 8UC1, non-zero: pixels of moving things (dilated); empty = none
};

// What the mapping side changed in the map after a keyframe: the poses and landmarks local BA
// moved, or after a loop closure the whole map, and the keyframes it erased. Whoever keeps a
// copy of the map (mapping_node, the dense maps) applies it. Mirrored by msg/MapUpdateMsg.msg.
struct MapUpdate {
  struct KeyFramePose {
    long id = 0;
    // World -> camera, as the map keeps it: a copy of the map gets the mapping side's pose
    // bit for bit (an inverse taken twice would not give it back).
    Eigen::Isometry3d T_cw = Eigen::Isometry3d::Identity();
    long parent = -1;  // in the spanning tree; -1: none (the first keyframe)
    Eigen::Isometry3d T_wc() const { return T_cw.inverse(); }
  };
  double stamp = 0.0;  // of the newest keyframe it accounts for
  std::vector<KeyFramePose> keyframes;
  std::vector<LandmarkPoint> points;
  std::vector<LandmarkLine> lines;
  std::vector<long> erased_keyframes;  // culled as redundant
  bool whole_map = false;              // every keyframe and landmark (after a loop closure)
  // Point landmarks that left the map since the last update (culled, merged, dropped by BA):
  // without them a copy of the map keeps every point ever made.
  std::vector<long> erased_points;
  // Line landmarks that left the map since the last update (every keyframe that saw them erased).
  std::vector<long> erased_lines;
  // The point links of the keyframe this update maps, as the mapping side made them from the
  // tracker's report. A copy that went on meanwhile followed merges in another order and may
  // hold a merged point at another keypoint; it takes these before the journal, which then does
  // on both the same. keyframe -1: none (in line, or no keyframe).
  struct KeyFrameLinks {
    long keyframe = -1;
    std::vector<std::pair<size_t, long>> points;  // (keypoint, point id), by keypoint
  };
  KeyFrameLinks replayed;
  // Who sees what, changed in this order (merges, outliers unlinked, erasures): with the values
  // above, what a copy of the map needs to follow (Map::apply).
  MapJournal journal;
  // How the mapping side moved the world meanwhile (loop corrections, global bundle adjustments
  // written back), in order: T_wc(after) = correction * T_wc(before) for the newest keyframe it
  // had. Whoever tracks in a copy moves along (Tracker::applyCorrection).
  std::vector<Eigen::Isometry3d> world_corrections;
};

}  // namespace ply_slam
