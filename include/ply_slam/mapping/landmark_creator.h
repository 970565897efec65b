#pragma once

#include <memory>
#include <unordered_map>
#include <vector>

#include "ply_slam/common/pinhole_camera.h"
#include "ply_slam/features/line_options.h"
#include "ply_slam/map/map.h"
#include "ply_slam/map/tracker_report.h"
#include "ply_slam/tracking/landmark_sink.h"

namespace ply_slam {

// The mapping side's intake of what tracking measured (LandmarkSink): makes keyframes and their
// new landmarks from tracked frames, averages each measurement into the landmark it matched
// (a keyframe's depths into its points, every tracked frame's 3D line fits into its lines) and
// keeps the visible / found counts that map-point culling reads.
class LandmarkCreator : public LandmarkSink {
 public:
  // `max_point_depth` (tracking.max_point_depth): deeper features make no landmark and add no
  // depth to one. `lines`: lines.enabled, and the angle a fit may differ from its line.
  LandmarkCreator(const PinholeCamera& camera, double max_point_depth, const LineOptions& lines,
                  Map& map);

  void countVisible(const std::vector<MapPoint*>& in_view) override;
  void recordTracked(const Frame& frame, bool fuse_lines) override;
  std::shared_ptr<KeyFrame> addKeyFrame(Frame& frame) override;

  // Writes what the calls above do into `report` (by id) as well, until called with nullptr.
  void reportTo(TrackerReport* report) { report_ = report; }
  // Points this map merged away (loser id -> winner id) that another copy may still name.
  using MergedPoints = std::unordered_map<long, long>;
  // Does to this creator's map what `report` says another creator did to its own copy:
  // counts, line fits, then `keyframe` (that creator's keyframe with its features and pose,
  // without links; its id kept) with its links and new landmarks (ids kept). What it says of a
  // point in `merged` goes to the point it was merged into, as that copy does when it follows
  // the merge (a link only where the keyframe does not see that point already). Links to a
  // landmark this map no longer has are left out. Returns the keyframe. Throws
  // std::invalid_argument, changing nothing, when the report is of another keyframe.
  std::shared_ptr<KeyFrame> replay(const TrackerReport& report, std::shared_ptr<KeyFrame> keyframe,
                                   const MergedPoints& merged = {});

 private:
  void addPoints(Frame& frame, KeyFrame& keyframe);
  void addLines(Frame& frame, KeyFrame& keyframe);
  // Averages each accepted 3D fit of a tracked frame into the map line it matched as an
  // inlier, where the fit lies on that line.
  void fuseLineFits(const Frame& frame);
  // The fit (camera frame at T_wc) in the world, each end weighted by the inverse variance of
  // its depth.
  TrackerReport::LineFit worldFit(const MapLine& line, const Line3D& fit,
                                  const Eigen::Isometry3d& T_wc) const;
  using PointsById = std::unordered_map<long, std::shared_ptr<MapPoint>>;
  using LinesById = std::unordered_map<long, std::shared_ptr<MapLine>>;
  void replayPoints(const std::vector<TrackerReport::PointLink>& links, const PointsById& points,
                    const MergedPoints& merged, KeyFrame& keyframe);
  void replayLines(const std::vector<TrackerReport::LineLink>& links, const LinesById& lines,
                   KeyFrame& keyframe);
  // Inverse variance of a point at depth z seen at the scale of pyramid level `scale`: depth
  // noise along the ray, the keypoint's footprint across it.
  double pointWeight(double z, double scale) const;

  const PinholeCamera camera_;
  const double max_point_depth_;
  const bool lines_enabled_;
  const double line_match_angle_deg_;
  Map& map_;
  TrackerReport* report_ = nullptr;
};

}  // namespace ply_slam
