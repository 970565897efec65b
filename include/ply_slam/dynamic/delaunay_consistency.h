#pragma once

#include <Eigen/Geometry>
#include <vector>

#include "ply_slam/common/config.h"

namespace ply_slam {

// One feature matched between the previous and the current frame, with its 3D position in
// each frame's camera coordinates (distances between points do not depend on the frame).
struct FeatureCorrespondence {
  Eigen::Vector2d pixel;     // current frame, undistorted
  Eigen::Vector3d previous;  // previous camera frame (m)
  Eigen::Vector3d current;   // current camera frame (m)
};

// The Delaunay topology check of PAPER.md §3.2: a triangle network over the matched features
// in the current image; each edge compares the 3D distance between its two features in the
// previous and the current frame, which a rigid static scene keeps. The dynamic weight of a
// feature is the share of its edges that changed more than the noise allows: the endpoints'
// covariances (depth noise sigma_Z^2 along the ray, pixel noise across it, as in §3.1)
// projected on the edge. Beyond the paper: features joined by consistent edges form rigid
// bodies, and a body clearly smaller than the largest (the static scene) moved as a whole —
// its inner edges never break, so the per-edge vote alone sees only its rim; and the camera
// motion fitted to the largest body must carry each feature onto its current position.
class DelaunayConsistency {
 public:
  DelaunayConsistency(const PinholeCamera& camera, const DelaunayConsistencyParams& params)
      : camera_(camera), params_(params) {}

  // Weight in [0, 1] per correspondence (0 for features without edges).
  std::vector<double> weights(const std::vector<FeatureCorrespondence>& features, int width,
                              int height) const;

 private:
  // A change in metres and in standard deviations of its modelled noise.
  struct Change {
    double metres = 0.0, sigmas = 0.0;
  };
  Change edgeChange(const FeatureCorrespondence& a, const FeatureCorrespondence& b) const;
  // How far `motion` leaves the feature's previous position from its current one.
  Change residual(const FeatureCorrespondence& f, const Eigen::Isometry3d& motion) const;
  // Beyond min_change and beyond sigma_factor standard deviations of the scaled noise.
  bool exceeds(const Change& change, double scale) const;
  // How much larger than modelled the noise of mostly static measurements is (>= 1), from the
  // median of their normalised changes and that median for unit noise.
  static double noiseScale(const std::vector<double>& sigmas, double median_of_unit);

  // Variance of a back-projected point along unit direction d: depth noise along its ray,
  // pixel noise across it.
  double varianceAlong(const Eigen::Vector3d& p, const Eigen::Vector3d& d) const;
  // Least-squares rigid motion previous -> current of the features flagged in `use`.
  Eigen::Isometry3d rigidMotion(const std::vector<FeatureCorrespondence>& features,
                                const std::vector<bool>& use) const;

  PinholeCamera camera_;
  DelaunayConsistencyParams params_;
};

}  // namespace ply_slam
