#pragma once

#include <Eigen/Geometry>
#include <vector>

#include "ply_slam/common/chi_square.h"
#include "ply_slam/common/pinhole_camera.h"
#include "ply_slam/common/solver_options.h"
#include "ply_slam/features/line_options.h"

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

// F(n) of the line term (LineBalance) for n point observations.
double lineBalanceFactor(LineBalance balance, int num_points);

// Each round's solve: from a predicted or already refined pose, a few iterations suffice. A round
// stops once an iteration changes the cost by less than 1e-3 of it: Ceres' 1e-6 only bought
// iterations (with lines 5.5 instead of 2.2 per round, same ATE; docs/RESULTS.md, "Lines in
// tracking"). One pose has six unknowns: dense QR.
inline SolverOptions poseSolverDefaults() {
  SolverOptions o;
  o.linear_solver = LinearSolver::kDenseQr;
  o.max_iterations = 10;
  o.function_tolerance = 1e-3;
  return o;
}

struct PoseOptimizerParams {
  double chi2_pixel = kChiSquare95TwoDof;       // reprojection outlier above
  double chi2_depth = kChiSquare95ThreeDof;     // with the depth residual
  int rounds = 4;                               // solve, re-classify outliers, repeat
  SolverOptions solver = poseSolverDefaults();  // per round
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
