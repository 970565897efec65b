#pragma once

#include <Eigen/Core>
#include <vector>

#include "ply_slam/common/pinhole_camera.h"

namespace ply_slam {

// One feature matched between the previous and the current frame, with its 3D position in
// each frame's camera coordinates (distances between points do not depend on the frame).
struct FeatureCorrespondence {
  Eigen::Vector2d pixel;     // current frame, undistorted
  Eigen::Vector3d previous;  // previous camera frame (m)
  Eigen::Vector3d current;   // current camera frame (m)
};

struct DelaunayConsistencyParams {
  double sigma_factor = 3.0;  // an edge is inconsistent when its length changes > k sigma
  double min_change = 0.02;   // m; and by at least this much (unmodelled errors)
};

// The Delaunay topology check of PAPER.md §3.2: a triangle network over the matched features
// in the current image; each edge compares the 3D distance between its two features in the
// previous and the current frame, which a rigid static scene keeps. The dynamic weight of a
// feature is the share of its edges that changed more than the depth noise allows.
class DelaunayConsistency {
 public:
  DelaunayConsistency(const DepthNoiseModel& noise, const DelaunayConsistencyParams& params)
      : noise_(noise), params_(params) {}

  // Weight in [0, 1] per correspondence (0 for features without edges).
  std::vector<double> weights(const std::vector<FeatureCorrespondence>& features, int width,
                              int height) const;

 private:
  bool inconsistent(const FeatureCorrespondence& a, const FeatureCorrespondence& b) const;

  DepthNoiseModel noise_;
  DelaunayConsistencyParams params_;
};

}  // namespace ply_slam
