#pragma once

#include "ply_slam/mapping/pose_graph_options.h"

namespace ply_slam {

// How an accepted loop is closed in the map (LoopCorrector); the config's loop_correction
// section.
struct LoopCorrectionOptions {
  // Keyframes sharing at least this many landmarks get a pose-graph edge of their own besides
  // the spanning tree: ORB-SLAM's essential graph uses 100.
  int strong_covisibility = 100;
  // Keyframes of the old side (the loop keyframe and its best covisible ones) whose landmarks
  // are fused into the current side. ORB-SLAM fuses the loop keyframe's covisible group.
  int loop_side_keyframes = 10;
  // A loop is closed only if the correction it asks for is drift the tracker could have
  // gathered on the way: at most max_drift_floor_m + max_drift_fraction x the path walked since
  // the loop keyframe, and as many degrees by the rotation terms. A repeated texture (tiled
  // walls, a row of identical doors) passes the geometric check with a pose metres off; RGB-D
  // odometry of this kind drifts ~1-2 % of the distance (TUM RPE), so 5 % leaves room.
  double max_drift_fraction = 0.05;
  double max_drift_floor_m = 0.1;
  double max_rotation_drift_deg_per_m = 1.0;
  double max_rotation_drift_floor_deg = 3.0;
  // After a loop is closed, this many keyframes pass before the next query: the keyframes
  // right after a loop see the same old place and would close it again (ORB-SLAM: 10).
  int min_keyframes_between = 10;
  PoseGraphOptions pose_graph;
  // Bundle adjustment of the whole map after the pose graph (0: none). The graph moves
  // keyframes as rigid bodies along the chain; only landmarks seen from both visits re-tie the
  // middle. ORB-SLAM runs 10 iterations.
  int global_ba_iterations = 10;
};

}  // namespace ply_slam
