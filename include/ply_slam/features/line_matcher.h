#pragma once

#include <Eigen/Geometry>
#include <vector>

#include "ply_slam/common/config.h"
#include "ply_slam/common/pinhole_camera.h"
#include "ply_slam/features/frame_lines.h"

namespace ply_slam {

// A line of frame A matched to a line of frame B.
struct LineMatch {
  int a = -1, b = -1;
  int distance = 0;  // LBD Hamming distance
};

// Matches lines between two frames by LBD Hamming distance.
class LineMatcher {
 public:
  LineMatcher(const LineParams& params, const PinholeCamera& camera);

  // Geometry first: each 3D segment of A is moved into B by the predicted pose T_ba (A's camera
  // to B's) and projected; B's segments within the gates (direction within match_angle_deg,
  // both projected endpoints within match_distance_px of B's line, overlapping along it) are
  // the candidates, the closest descriptor below max_descriptor_distance wins if it beats the
  // second-best by match_ratio. Each B segment goes to its best A segment only. A's segments
  // without a 3D fit are not matched.
  std::vector<LineMatch> matchProjected(const FrameLines& a, const FrameLines& b,
                                        const Eigen::Isometry3d& T_ba) const;
  // Descriptors only: mutual nearest neighbours below max_descriptor_distance that pass the
  // ratio test, for when no pose is predicted.
  std::vector<LineMatch> matchDescriptors(const FrameLines& a, const FrameLines& b) const;

  // Whether B's segment passes the gates for the projected segment (ps, pe), undistorted px.
  bool withinGates(const Eigen::Vector2d& ps, const Eigen::Vector2d& pe,
                   const LineFeature& observed) const;

 private:
  LineParams params_;
  PinholeCamera camera_;
  double cos_max_angle_;
};

}  // namespace ply_slam
