#pragma once

#include "ply_slam/common/solver_options.h"

namespace ply_slam {

// Settings of the SE(3) pose graph that corrects keyframe poses after a loop. Each value says
// where it comes from; the paper gives none.
struct PoseGraphOptions {
  // Levenberg-Marquardt iterations at most. ORB-SLAM's essential-graph optimisation runs 20;
  // in test_pose_graph a 20-40 pose square with 1-5 deg of drift converges in 3-5, a 500-pose
  // circle with 1-16 deg in 9-10.
  int max_iterations = 20;
  // An edge's standard deviations, one per rotation axis and per translation axis. With every
  // edge weighted alike only their ratio moves the solution: how many metres of translation
  // error weigh as much as one radian of rotation error. Ours: the tracker's per-frame RPE on
  // fr1_xyz and fr1_rpy, 0.36-0.41 deg (~0.007 rad) and 4-6 mm (docs/RESULTS.md).
  double rotation_sigma_rad = 0.007;
  double translation_sigma_m = 0.005;
  // Ceres threads for the Jacobians. 1: the mapper runs beside the tracker on a two-core
  // robot computer, and a 500-keyframe graph solves in tens of ms on one core.
  int num_threads = 1;
  // Each pose touches only its few neighbours: the normal equations are sparse.
  LinearSolver linear_solver = LinearSolver::kSparseNormalCholesky;
};

}  // namespace ply_slam
