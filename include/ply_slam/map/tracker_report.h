#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <map>
#include <memory>
#include <vector>

#include "ply_slam/map/map_line.h"
#include "ply_slam/map/map_point.h"

namespace ply_slam {

// What the tracker did to the map from one keyframe to the next, by landmark id: the counts and
// line fits of its tracked frames and how the new keyframe ties to the map. Replayed on another
// copy of the map (LandmarkCreator::replay) it leaves that copy as the tracker left its own,
// which is what lets the mapping side keep a map of its own (issue 17, the two-process split).
struct TrackerReport {
  struct Counts {
    int visible = 0;  // MapPoint::visible gained
    int found = 0;    // MapPoint::found / MapLine::found gained
  };
  // An accepted 3D line fit of a tracked frame, world frame, as fused into line `id`.
  struct LineFit {
    long id = 0;
    Eigen::Vector3d start = Eigen::Vector3d::Zero(), end = Eigen::Vector3d::Zero();
    double start_weight = 0.0, end_weight = 0.0;
  };
  // Keypoint `keypoint` of the keyframe tied to point `id`: one it made (`created`: its state
  // then, without links) or one it saw again, with the depth measurement fused into it
  // (`weight` 0: none).
  struct PointLink {
    size_t keypoint = 0;
    long id = 0;
    std::shared_ptr<const MapPoint> created;
    Eigen::Vector3d measured = Eigen::Vector3d::Zero();
    double weight = 0.0;
  };
  // Line `line` of the keyframe tied to line landmark `id`, made by it (`created`) or seen again.
  struct LineLink {
    size_t line = 0;
    long id = 0;
    std::shared_ptr<const MapLine> created;
  };

  std::map<long, Counts> points;   // by point id
  std::map<long, int> lines;       // line id -> found gained
  std::vector<LineFit> line_fits;  // in the order fused
  // The keyframe, made after the fits above (the counts commute with everything here): its id
  // (-1: none yet) and its links in the order made.
  long keyframe = -1;
  std::vector<PointLink> point_links;
  std::vector<LineLink> line_links;
};

// The report moved rigidly with the world (`move`: T_world'_world, a world correction): the line
// fits, the points and lines the keyframe made and the depths it fused.
void moveTrackerReport(TrackerReport& report, const Eigen::Isometry3d& move);

}  // namespace ply_slam
