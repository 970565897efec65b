#pragma once

#include <Eigen/Geometry>
#include <cstddef>

#include "ply_slam/common/angles.h"           // rotationAngleDeg
#include "ply_slam/common/rigid_alignment.h"  // the ATE aligns with alignRigid
#include "ply_slam/common/stamped_pose.h"

namespace ply_slam {

struct ErrorStats {
  size_t count = 0;
  double rmse = 0.0, mean = 0.0, median = 0.0, max = 0.0;
};

struct AteResult {
  ErrorStats translation;                                      // m, after alignment
  Eigen::Isometry3d T_gt_est = Eigen::Isometry3d::Identity();  // maps estimate into gt frame
};

// The ATE after a similarity alignment: what is left once the estimate's scale is fitted too.
struct SimilarityAteResult {
  ErrorStats translation;  // m, after alignment
  double scale = 1.0;      // > 1: the estimate is smaller than the truth
};

struct RpeResult {
  ErrorStats translation;  // m
  ErrorStats rotation;     // degrees
};

// Absolute trajectory error, TUM definition: associate stamps within max_dt, align, RMSE etc.
// Throws std::runtime_error when fewer than 3 pairs associate.
AteResult computeAte(const Trajectory& gt, const Trajectory& est, double max_dt = 0.02);
// The same aligned with a scale (Sim(3)).
SimilarityAteResult computeAteSimilarity(const Trajectory& gt, const Trajectory& est,
                                         double max_dt = 0.02);
// The same with the alignment given, not fitted: a run in a loaded map is judged in that map's
// frame, with the alignment of the run that made the map (a free fit would hide an offset).
AteResult computeAteInFrame(const Trajectory& gt, const Trajectory& est,
                            const Eigen::Isometry3d& T_gt_est, double max_dt = 0.02);

// Relative pose error, TUM definition, over pairs of associated poses `delta_frames` apart
// (in the estimate's order) or `delta_seconds` apart.
RpeResult computeRpeFrames(const Trajectory& gt, const Trajectory& est, int delta_frames,
                           double max_dt = 0.02);
RpeResult computeRpeSeconds(const Trajectory& gt, const Trajectory& est, double delta_seconds,
                            double max_dt = 0.02);

}  // namespace ply_slam
