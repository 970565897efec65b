#pragma once

#include "ply_slam/common/chi_square.h"
#include "ply_slam/common/solver_options.h"

namespace ply_slam {

// Local bundle adjustment after each keyframe: a small window that starts from good poses, so
// a few iterations; poses and points, so the Schur complement on the sparse structure. (The
// global bundle adjustment after a loop sets its own iterations, loop_correction.)
inline SolverOptions bundleSolverDefaults() {
  SolverOptions o;
  o.linear_solver = LinearSolver::kSparseSchur;
  o.max_iterations = 10;
  return o;
}

// The mapping side's work around a new keyframe: landmark fusion and local bundle adjustment.
struct LocalMappingOptions {
  // Covisible keyframes around a new keyframe that fusion, bundle adjustment and culling take.
  // Loaded from tracking.local_map_keyframes: the tracker's local map is the same window.
  int window_keyframes = 10;
  // 2-DoF outlier bound of an observation (the 3-DoF one with depth, withDepthDof). Loaded from
  // tracking.chi2_outlier: a point the tracker keeps is not an outlier here.
  double chi2_outlier = kChiSquare95TwoDof;
  // Landmark fusion: a landmark is looked for within this radius (px at pyramid level 0, scaled
  // with the level) of its projection, and taken below this Hamming distance: stricter than
  // tracking's, a merge is permanent.
  double fuse_radius_px = 3.0;
  int fuse_max_descriptor_distance = 50;
  SolverOptions bundle_solver = bundleSolverDefaults();  // the `mapping:` section's bundle_solver
};

}  // namespace ply_slam
