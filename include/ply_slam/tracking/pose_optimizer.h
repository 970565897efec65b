#pragma once

#include <Eigen/Geometry>
#include <vector>

#include "ply_slam/common/pinhole_camera.h"

namespace ply_slam {

// One landmark seen in the current frame.
struct PointObservation {
  Eigen::Vector3d world;     // landmark position, world frame (m)
  Eigen::Vector2d pixel;     // undistorted observation (px)
  double pixel_sigma = 1.0;  // px; grows with the pyramid level
  double depth = 0.0;        // measured depth (m), 0 when the pixel has none
  double depth_sigma = 0.0;  // m, from the sensor noise model
};

// One line landmark seen in the current frame (PAPER.md §3): the 3D segment's world endpoints
// and the observed 2D segment as its normalised homogeneous line l = (p_s^h x p_e^h) / |(a, b)|.
struct LineObservation {
  Eigen::Vector3d start, end;  // world frame (m)
  Eigen::Vector3d line;        // l . (u, v, 1) = signed distance in px (undistorted)
  double pixel_sigma = 1.0;    // px, of the observed line's position
};

// How the line term is weighted against the point term: F(n) of PAPER.md §3, with n the
// number of point observations. kPaper reads the garbled "F(n) = 2 n 50" as 2n/50; kOne is 1.
enum class LineBalance { kPaper, kOne };
double lineBalanceFactor(LineBalance balance, int num_points);

struct PoseOptimizerParams {
  double chi2_pixel = 5.991;  // 2-DoF 95 %: reprojection outlier above
  double chi2_depth = 7.815;  // 3-DoF 95 %: with the depth residual
  int rounds = 4;             // solve, re-classify outliers, repeat
  int max_iterations = 10;    // per round
  // A round stops once an iteration changes the cost by less than this share: the solve
  // starts from a predicted or already refined pose, and Ceres' 1e-6 only bought iterations
  // (with lines 5.5 instead of 2.2 per round, same ATE; docs/RESULTS.md, "Lines in tracking").
  double function_tolerance = 1e-3;
};

// Camera pose from point (and, in the second overload, line) correspondences with Ceres:
// whitened reprojection error (plus a depth residual where the pixel has depth), Huber
// kernel, and rounds that re-classify every observation as inlier or outlier against the
// chi-square bounds.
class PoseOptimizer {
 public:
  PoseOptimizer(const PinholeCamera& camera, const PoseOptimizerParams& params);

  // Refines T_cw in place; inlier[i] tells whether observation i fits. Returns inliers.
  int optimize(const std::vector<PointObservation>& observations, Eigen::Isometry3d& T_cw,
               std::vector<bool>& inlier) const;
  // Points and lines together: cost sum rho(e_p' A^-1 e_p) + sum rho(F e_l' B^-1 e_l) with
  // e_l = [l . pi^h(T_cw P_s), l . pi^h(T_cw P_e)] (px, whitened by the line's pixel_sigma),
  // Huber rho, F = line_weight. Lines are re-classified like points against the 2-DoF bound
  // (chi2_pixel) on the unweighted e_l' B^-1 e_l. Returns the point inliers; line_inlier[k]
  // tells whether line k fits.
  int optimize(const std::vector<PointObservation>& observations,
               const std::vector<LineObservation>& lines, double line_weight,
               Eigen::Isometry3d& T_cw, std::vector<bool>& inlier,
               std::vector<bool>& line_inlier) const;
  // Whitened squared line error e_l' B^-1 e_l at T_cw (infinite behind the camera).
  double squaredLineError(const LineObservation& o, const Eigen::Isometry3d& T_cw) const;

 private:
  double squaredError(const PointObservation& o, const Eigen::Isometry3d& T_cw) const;

  PinholeCamera camera_;
  PoseOptimizerParams params_;
};

}  // namespace ply_slam
