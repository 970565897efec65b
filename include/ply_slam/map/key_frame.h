#pragma once

#include <Eigen/Geometry>
#include <map>
#include <memory>
#include <vector>

#include "ply_slam/features/frame_features.h"
#include "ply_slam/map/map_line.h"
#include "ply_slam/map/map_point.h"

namespace ply_slam {

// A frame kept in the map: its features, pose and the landmarks it observes.
struct KeyFrame {
  long id = 0;
  long frame_id = 0;
  double stamp = 0.0;
  Eigen::Isometry3d T_cw = Eigen::Isometry3d::Identity();
  FrameFeatures features;
  std::vector<std::shared_ptr<MapPoint>> map_points;  // per keypoint, may be null
  std::vector<std::shared_ptr<MapLine>> map_lines;    // per line of the frame, may be null
  std::map<KeyFrame*, int> covisibility;              // keyframe -> shared map points
  // Spanning tree (the pose graph's backbone): the keyframe this one shared the most landmarks
  // with when it joined the map; null for the first. Set by the mapping side.
  KeyFrame* parent = nullptr;
  bool bad = false;  // erased from the map (culled); holds no links to other keyframes

  Eigen::Isometry3d T_wc() const { return T_cw.inverse(); }
  // The keyframe as another copy of the map first gets it: id, features and pose, no links
  // (that copy links it as a TrackerReport says).
  std::shared_ptr<KeyFrame> unlinkedCopy() const;
  int trackedPoints(int min_observations = 1) const;
  // Up to n keyframes sharing the most landmarks with this one, most first.
  std::vector<KeyFrame*> bestCovisible(size_t n) const;
  // The older keyframe (smaller id) sharing the most landmarks with this one, null if none: a
  // spanning-tree parent, older so that the tree has no cycle even when the tracker has made
  // newer keyframes that share more (the mapping thread behind).
  KeyFrame* bestOlderCovisible() const;
};

}  // namespace ply_slam
