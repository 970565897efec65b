#pragma once

#include <Eigen/Geometry>
#include <memory>
#include <vector>

#include "ply_slam/features/frame_features.h"
#include "ply_slam/features/frame_lines.h"
#include "ply_slam/map/map_line.h"
#include "ply_slam/map/map_point.h"

namespace ply_slam {

// The frame being tracked: features, pose estimate and the landmark matched to each feature.
struct Frame {
  long id = 0;
  double stamp = 0.0;
  FrameFeatures features;
  std::vector<std::shared_ptr<MapPoint>> map_points;  // per keypoint, may be null
  std::vector<bool> outlier;                          // per keypoint, set by pose optimisation
  Eigen::Isometry3d T_cw = Eigen::Isometry3d::Identity();
  // Line features (empty when lines are disabled) and the line landmark matched to each.
  FrameLines lines;
  std::vector<std::shared_ptr<MapLine>> map_lines;  // per line, may be null
  std::vector<bool> line_outlier;                   // per line, set by pose optimisation

  Frame() = default;
  Frame(long frame_id, double frame_stamp, FrameFeatures frame_features)
      : id(frame_id),
        stamp(frame_stamp),
        features(std::move(frame_features)),
        map_points(features.size()),
        outlier(features.size(), false) {}

  Eigen::Vector3d cameraCentre() const { return T_cw.inverse().translation(); }
  // Attaches the frame's line features (before tracking).
  void setLines(FrameLines frame_lines);
  int numMatches() const;
  int numLineMatches() const;
  void clearMatches();  // points and lines
};

}  // namespace ply_slam
