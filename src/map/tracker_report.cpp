#include "ply_slam/map/tracker_report.h"

namespace ply_slam {

void moveTrackerReport(TrackerReport& report, const Eigen::Isometry3d& move) {
  for (auto& fit : report.line_fits) {
    fit.start = move * fit.start;
    fit.end = move * fit.end;
  }
  for (auto& link : report.point_links) {
    link.measured = move * link.measured;
    if (!link.created) continue;
    auto moved = std::make_shared<MapPoint>(*link.created);  // shared with the tracker's copy
    moved->moveBy(move);
    link.created = std::move(moved);
  }
  for (auto& link : report.line_links) {
    if (!link.created) continue;
    auto moved = std::make_shared<MapLine>(*link.created);
    moved->moveBy(move);
    link.created = std::move(moved);
  }
}

}  // namespace ply_slam
