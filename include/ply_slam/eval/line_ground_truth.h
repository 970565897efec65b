#pragma once

#include <Eigen/Geometry>
#include <vector>

#include "ply_slam/common/pinhole_camera.h"
#include "ply_slam/features/line_feature.h"
#include "ply_slam/synth/segment3.h"

namespace ply_slam {

// How far a reconstructed 3D segment is from the true segment it belongs to.
struct LineError {
  double endpoint_m = 0.0;  // the larger distance of its two ends to the true segment
  double angle_deg = 0.0;   // between the two directions
};

LineError lineError(const Eigen::Vector3d& start, const Eigen::Vector3d& end,
                    const Segment3& truth);
// The error against the nearest of several candidate true segments (indices into truth, from
// imagedSegments): the one with the smallest endpoint distance. Not empty.
LineError lineError(const Eigen::Vector3d& start, const Eigen::Vector3d& end,
                    const std::vector<Segment3>& truth, const std::vector<size_t>& candidates);

// The true segments a detected 2D segment may image: those whose projection (camera at T_cw)
// has both detected ends within `max_px` of its line, a direction within `max_deg`, and
// overlaps it (segments one behind the other can image alike). Texture edges inside surfaces
// have none.
std::vector<size_t> imagedSegments(const LineFeature& line, const std::vector<Segment3>& truth,
                                   const PinholeCamera& camera, const Eigen::Isometry3d& T_cw,
                                   double max_px = 2.0, double max_deg = 2.0);

}  // namespace ply_slam
