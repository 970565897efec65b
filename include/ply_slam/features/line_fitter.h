#pragma once

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <vector>

#include "ply_slam/common/measured_point_noise.h"
#include "ply_slam/common/pinhole_camera.h"
#include "ply_slam/features/line_3d.h"
#include "ply_slam/features/line_depth_refiner.h"
#include "ply_slam/features/line_feature.h"
#include "ply_slam/features/line_options.h"
#include "ply_slam/features/registered_depth.h"

namespace ply_slam {

// 3D line segments from a 2D segment and a depth image (CV_32F metres, 0 = invalid,
// registered to the raw rgb image).
//
// fitSampled is PAPER.md §3.1: N = min(L_avg, floor(length)), samples j = 0..N spread
// uniformly between the undistorted endpoints, each back-projected with the depth read at its
// raw pixel (samples without depth skipped), with covariance J Λ Jᵀ (Λ = diag(σ_px², σ_px²,
// σ_Z²(Z))); two-point RANSAC with a Mahalanobis inlier test (chi2_inlier); PCA on the largest
// inlier set; endpoints at the extreme inlier projections; accepted when
// inliers / (N + 1) > Th1 (min_inlier_ratio) and the 3D length > Th2 (min_length_m).
// Additions: each sample's depth comes from depthNear (at an occluding edge the nearer side's,
// always; where the depth is invalid, the nearest valid one up to depth_search_px across the
// line); refit_rounds re-selections of the inliers against the PCA line; and the accepted
// line's depth re-read from the surfaces beside it (LineDepthRefiner, surface_band_px).
// depth_search_px = refit_rounds = surface_band_px = 0: the paper's fit but for the
// nearer-side read at occluding edges.
// fitEndpoints is the "traditional" method: the two endpoints back-projected with their own
// depth (found the same way), the same acceptance with the two endpoints as its samples.
// Not thread-bound: const, no state per call.
class LineFitter {
 public:
  LineFitter(const LineOptions& params, const PinholeCamera& camera);

  Line3D fitSampled(const LineFeature& line, const cv::Mat& depth_m, int average_length) const;
  Line3D fitEndpoints(const LineFeature& line, const cv::Mat& depth_m) const;

  // RANSAC, PCA, endpoints and acceptance on back-projected samples in order along the line
  // (their covariances beside them); num_samples counts those without depth too.
  Line3D fitPoints(const std::vector<Eigen::Vector3d>& points,
                   const std::vector<Eigen::Matrix3d>& covariances, int num_samples) const;

  // Σ = J Λ Jᵀ of the point back-projected from undistorted pixel uv with depth z
  // (MeasuredPointNoise with lines.sigma_px).
  Eigen::Matrix3d sampleCovariance(const Eigen::Vector2d& uv, double z) const;
  // Squared Mahalanobis distance of p to the line through a with direction d, given p's
  // information matrix info = Σ⁻¹ (the RANSAC and refit inlier test of fitPoints).
  static double mahalanobisToLine(const Eigen::Vector3d& p, const Eigen::Matrix3d& info,
                                  const Eigen::Vector3d& a, const Eigen::Vector3d& d);
  // L_avg = ceil(mean 2D length) of a frame's segments.
  static int averageLength(const std::vector<LineFeature>& lines);

  // Depth (m) at raw pixel `raw` (RegisteredDepth::atRaw), but where it is invalid the depth
  // of the nearest valid pixel up to depth_search_px away along `raw_across` (one px across
  // the line, in raw pixels), either side; at an occluding edge the nearer side's.
  double depthNear(const cv::Mat& depth_m, const Eigen::Vector2d& raw,
                   const Eigen::Vector2d& raw_across) const;

 private:
  bool accept(Line3D& line) const;

  LineOptions params_;
  PinholeCamera camera_;
  MeasuredPointNoise noise_;  // of the samples, with lines.sigma_px
  RegisteredDepth depth_;
  LineDepthRefiner refiner_;
};

}  // namespace ply_slam
