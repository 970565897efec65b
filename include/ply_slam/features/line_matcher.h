#pragma once

#include <Eigen/Geometry>
#include <vector>

#include "ply_slam/common/pinhole_camera.h"
#include "ply_slam/features/frame_lines.h"
#include "ply_slam/features/line_options.h"

namespace ply_slam {

// A line of frame A matched to a line of frame B.
struct LineMatch {
  int a = -1, b = -1;
  int distance = 0;  // LBD Hamming distance
};

// A 3D segment to project and match (a line landmark, or a frame's 3D fit) and its LBD
// descriptor: 32 bytes that must outlive the matching.
struct SegmentToMatch {
  Eigen::Vector3d start = Eigen::Vector3d::Zero();
  Eigen::Vector3d end = Eigen::Vector3d::Zero();
  const uchar* descriptor = nullptr;
};

// Matches lines between two frames, or landmarks to a frame, by LBD Hamming distance.
class LineMatcher {
 public:
  LineMatcher(const LineOptions& params, const PinholeCamera& camera);

  // Geometry first: each segment is moved into B's camera by the predicted pose T_bs and
  // projected (ends nearer than 5 cm: not matched); B's segments within the gates (withinGates)
  // are the candidates, the closest descriptor below max_descriptor_distance wins if it beats
  // the second-best by match_ratio. Each B segment goes to its best segment only. LineMatch::a
  // indexes `segments`; sorted by it. The tracker matches its local map's lines with this.
  std::vector<LineMatch> matchSegments(const std::vector<SegmentToMatch>& segments,
                                       const FrameLines& b, const Eigen::Isometry3d& T_bs) const;
  // matchSegments with A's 3D segments and T_ba (A's camera to B's); LineMatch::a indexes A.
  // A's segments without a 3D fit are not matched.
  std::vector<LineMatch> matchProjected(const FrameLines& a, const FrameLines& b,
                                        const Eigen::Isometry3d& T_ba) const;
  // Descriptors only: mutual nearest neighbours below max_descriptor_distance that pass the
  // ratio test, for when no pose is predicted.
  std::vector<LineMatch> matchDescriptors(const FrameLines& a, const FrameLines& b) const;

  // Whether B's segment passes the gates for the projected segment (ps, pe), undistorted px:
  // both at least a pixel long, the projection not wholly off one side of the image, direction
  // within match_angle_deg, both projected ends within match_distance_px of B's line, and
  // overlapping along it.
  bool withinGates(const Eigen::Vector2d& ps, const Eigen::Vector2d& pe,
                   const LineFeature& observed) const;

 private:
  struct Projected;  // a projected segment
  struct Observed;   // an image segment, prepared once per frame

  // The projected segment's own gates, then the pair's: one implementation of each gate.
  bool projectedPasses(const Projected& p) const;
  bool pairPasses(const Projected& p, const Observed& o) const;
  // The best line of B for one segment by descriptor among those within the gates: kept when
  // it passes the distance and ratio tests.
  bool bestLine(const SegmentToMatch& s, const std::vector<Observed>& observed,
                const cv::Mat& descriptors, const Eigen::Isometry3d& T_bs, LineMatch& m) const;

  LineOptions params_;
  PinholeCamera camera_;
  double cos_max_angle_;
};

}  // namespace ply_slam
