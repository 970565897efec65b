#pragma once

#include <Eigen/Geometry>
#include <optional>
#include <vector>

#include "ply_slam/common/measured_point_noise.h"
#include "ply_slam/common/pinhole_camera.h"
#include "ply_slam/dynamic/delaunay_consistency_options.h"

namespace ply_slam {

// What is known, beside the features themselves, about which of them are static.
struct StaticPrior {
  // The camera's motion from the previous to the current frame as the tracker predicts it.
  const Eigen::Isometry3d* predicted_motion = nullptr;
  // Per feature: on an instance of a class that moves by itself (people, animals, vehicles).
  const std::vector<bool>* on_moving_class = nullptr;
};

// One feature matched between the previous and the current frame, with its 3D position in
// each frame's camera coordinates (distances between points do not depend on the frame).
struct FeatureCorrespondence {
  Eigen::Vector2d pixel;     // current frame, undistorted
  Eigen::Vector3d previous;  // previous camera frame (m)
  Eigen::Vector3d current;   // current camera frame (m)
  // The depth image's slope (dZ/du, dZ/dv, m/px) where each depth was read (depthSlopeAt).
  Eigen::Vector2d slope_previous = Eigen::Vector2d::Zero();
  Eigen::Vector2d slope_current = Eigen::Vector2d::Zero();
};

// The Delaunay topology check of PAPER.md §3.2: a triangle network over the matched features
// in the current image; each edge compares the 3D distance between its two features in the
// previous and the current frame, which a rigid static scene keeps. The dynamic weight of a
// feature is the share of its edges that changed more than the noise allows: the endpoints'
// covariances (depth noise sigma_Z^2 along the ray, pixel noise across it, as in §3.1)
// projected on the edge. Beyond the paper: features joined by consistent edges form rigid
// bodies (a body that moves as a whole never breaks its inner edges, so the per-edge vote
// alone sees only its rim); the static scene is taken from the features the predicted camera
// motion carries, else from the largest body's features off people, and the camera motion
// fitted to it must carry each feature onto its current position.
class DelaunayConsistency {
 public:
  DelaunayConsistency(const PinholeCamera& camera, const DelaunayConsistencyOptions& params)
      : noise_(camera, params.pixel_sigma), params_(params) {}

  // The camera's motion fitted to the static scene (previous -> current) and how much larger
  // than modelled the static features' noise was in this frame (>= 1).
  struct StaticFit {
    Eigen::Isometry3d motion = Eigen::Isometry3d::Identity();
    double noise_scale = 1.0;
    size_t inliers = 0;  // features it carries
  };

  // Weight in [0, 1] per correspondence (0 for features without edges). static_fit, when
  // given, receives the static scene's fit, or nothing when the scene was too small to fit.
  std::vector<double> weights(const std::vector<FeatureCorrespondence>& features, int width,
                              int height, const StaticPrior& prior = {},
                              std::optional<StaticFit>* static_fit = nullptr) const;

  // Whether `body` (the features of one object) moved apart from the static scene: most of
  // them follow one rigid motion of their own (RANSAC: wrong matches follow none), and that
  // motion carries their centre further from where the static motion does than noise allows
  // (as for one feature, the frame's noise scale included: rolling shutter and blur bend a
  // static surface's motion too).
  bool movedApart(const std::vector<FeatureCorrespondence>& body, const StaticFit& fit) const;

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

  struct EdgeGraph {
    std::vector<int> edges_of, bad_of;                             // per feature
    std::vector<std::vector<std::pair<size_t, bool>>> neighbours;  // (j, consistent)
  };
  struct Bodies {
    std::vector<int> of;       // per feature: body id, -1 without edges
    std::vector<size_t> size;  // per body
  };
  EdgeGraph buildGraph(const std::vector<FeatureCorrespondence>& features, int width,
                       int height) const;
  Bodies growBodies(const EdgeGraph& graph) const;
  // Enough features to fit a motion to with some redundancy.
  static constexpr size_t kMinSeeds = 10;
  static constexpr int kBodyRansacRounds = 30;  // triples tried for a body's own motion
  // Per feature: taken as static to fit the camera's motion to first; empty when nothing is
  // (no body with the 3 features a motion needs).
  std::vector<bool> staticSeeds(const std::vector<FeatureCorrespondence>& features,
                                const Bodies& bodies, const StaticPrior& prior) const;
  // Per feature: the motion fitted to the static features (starting from `inlier`) carries it
  // onto its current position.
  std::vector<bool> carriedByStaticMotion(const std::vector<FeatureCorrespondence>& features,
                                          std::vector<bool> inlier, StaticFit& fit) const;

  // Least-squares rigid motion previous -> current of the features flagged in `use`.
  Eigen::Isometry3d rigidMotion(const std::vector<FeatureCorrespondence>& features,
                                const std::vector<bool>& use) const;

  MeasuredPointNoise noise_;  // of the features, with dynamic.pixel_sigma
  DelaunayConsistencyOptions params_;
};

}  // namespace ply_slam
