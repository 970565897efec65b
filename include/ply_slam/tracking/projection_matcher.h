#pragma once

#include <memory>
#include <unordered_set>
#include <vector>

#include "ply_slam/common/pinhole_camera.h"
#include "ply_slam/features/registered_depth.h"
#include "ply_slam/tracking/frame.h"

namespace ply_slam {

// Hamming distance between two 256-bit ORB descriptors (rows of CV_8U, 32 bytes).
int descriptorDistance(const cv::Mat& a, const cv::Mat& b);

struct ProjectionMatchParams {
  double radius_px = 15.0;  // search radius at level 0; scaled by the level's scale
  int max_distance = 60;    // Hamming
  double nn_ratio = 0.9;    // best < ratio * second best
  double depth_gate = 0.1;  // relative depth disagreement allowed (plus 5 cm)
};

// Matches landmarks to the frame's features by projecting them with frame.T_cw and searching
// a window around the projection. `levels` (optional, parallel to `points`) fixes the
// expected pyramid level of each point; otherwise the level is predicted from distance.
// Features that already hold a landmark are left alone. A landmark behind something nearer
// in the frame's depth image (a person in front of the wall) is neither searched for nor
// appended to `in_view` (the landmarks in view, which the mapping side counts visible). Returns
// the number of new matches. `projected` (optional) collects the landmarks that passed the view
// gates, matched or not, so that a later pass over the same frame need not project them again.
class ProjectionMatcher {
 public:
  ProjectionMatcher(const PinholeCamera& camera, double log_scale, int num_levels)
      : camera_(camera), depth_(camera), log_scale_(log_scale), num_levels_(num_levels) {}

  int match(Frame& frame, const std::vector<std::shared_ptr<MapPoint>>& points,
            const std::vector<int>* levels, const ProjectionMatchParams& params,
            std::vector<MapPoint*>& in_view,
            std::unordered_set<const MapPoint*>* projected = nullptr) const;

 private:
  // Something in the depth image lies clearly in front of the landmark at pc.
  bool occluded(const Frame& frame, const Eigen::Vector2d& uv, const Eigen::Vector3d& pc,
                const ProjectionMatchParams& params) const;

  const PinholeCamera& camera_;
  RegisteredDepth depth_;
  double log_scale_;
  int num_levels_;
};

}  // namespace ply_slam
