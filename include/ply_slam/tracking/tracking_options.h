#pragma once

#include "ply_slam/common/chi_square.h"
#include "ply_slam/common/solver_options.h"
#include "ply_slam/tracking/pose_optimizer.h"

namespace ply_slam {

// Tracking (the config's `tracking:` section). The mapping side reads local_map_keyframes and
// chi2_outlier from this section too (LocalMappingOptions), so that one setting keeps both alike.
struct TrackingOptions {
  int search_radius_px = 15;                 // projection matching window at scale level 0
  int max_descriptor_distance = 60;          // Hamming, accept a match below this
  double nn_ratio = 0.9;                     // best / second best distance
  int min_tracked_points = 15;               // fewer inliers: tracking is lost
  int local_map_keyframes = 10;              // covisible keyframes whose points form the local map
  double chi2_outlier = kChiSquare95TwoDof;  // reprojection outlier above (2-DoF 95 %)
  int optimisation_rounds = 4;               // outlier re-classification rounds
  double keyframe_min_ratio = 0.7;      // new keyframe when tracked < ratio * reference keyframe's
  int keyframe_max_frames = 5;          // or after this many frames
  double keyframe_translation = 0.10;   // m, or after moving this far
  double keyframe_rotation_deg = 15.0;  // or after turning this far
  // ... but none while more keyframes than this wait for the mapping side (ORB-SLAM inserts
  // while fewer than 3 wait for local mapping): a mapping side that cannot keep up holds the
  // tracker back instead of queueing keyframes, with their images, without bound.
  int keyframe_max_unmapped = 3;
  // m; a tracked pose this far from the constant-velocity prediction is a wrong solve (a
  // camera does not move 15 cm beyond its prediction in one frame), not a motion: lost.
  double max_prediction_error = 0.15;
  int pnp_iterations = 200;  // RANSAC iterations when projection matching fails
  double pnp_reprojection_px = 4.0;
  int pnp_min_matches = 15;  // PnP (and relocalisation) needs this many matches, then inliers
  // s; a frame further than this from the last tracked one predicts no motion: beyond, the
  // last motion says little.
  double max_velocity_gap_s = 0.2;
  // m/s; relocalised later than that, the camera lies within max_prediction_error plus this
  // speed times the time since the last tracked frame. A person walking fast with the camera
  // (1.4 m/s is a usual walking pace); the TUM fr1 sequences average 0.06-0.41 m/s, a
  // TurtleBot3 drives at most 0.26 m/s. A robot picked up is carried at a walk too.
  double max_camera_speed = 2.0;
  double max_point_depth = 6.0;  // m; points beyond are not mapped (depth noise grows as Z^2)
  SolverOptions pose_solver = poseSolverDefaults();  // each round of pose optimisation
};

}  // namespace ply_slam
