#pragma once

#include <vector>

#include "ply_slam/common/pinhole_camera.h"
#include "ply_slam/features/line_feature.h"
#include "ply_slam/features/line_options.h"

namespace ply_slam {

// Joins the pieces into which LSD breaks one edge (noise, a faint stretch, lens distortion):
// two segments of the same polarity merge when their directions differ by less than
// merge_angle_deg, each one's endpoints lie within merge_distance_px of the other's line, and
// the gap between them along the line is at most merge_gap_px. Works on undistorted
// endpoints, where straight edges are straight; the raw endpoints follow the undistorted ones.
class LineMerger {
 public:
  explicit LineMerger(const LineOptions& params);

  // Merges until no pair qualifies; longer segments absorb shorter ones first.
  std::vector<LineFeature> merge(std::vector<LineFeature> lines) const;
  bool mergeable(const LineFeature& a, const LineFeature& b) const;

 private:
  double max_angle_rad_, max_distance_px_, max_gap_px_;
};

}  // namespace ply_slam
