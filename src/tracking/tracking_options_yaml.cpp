#include "ply_slam/tracking/tracking_options_yaml.h"

#include "ply_slam/common/solver_options_yaml.h"

namespace ply_slam {

TrackingOptions readTrackingOptions(ConfigSection s) {
  TrackingOptions t;
  s.readPositive("search_radius_px", t.search_radius_px);
  s.readPositive("max_descriptor_distance", t.max_descriptor_distance);
  s.readPositive("nn_ratio", t.nn_ratio);
  if (t.nn_ratio > 1.0) s.fail("nn_ratio", "must be <= 1");
  s.readPositive("min_tracked_points", t.min_tracked_points);
  s.readPositive("local_map_keyframes", t.local_map_keyframes);
  s.readPositive("chi2_outlier", t.chi2_outlier);
  s.readPositive("optimisation_rounds", t.optimisation_rounds);
  s.readPositive("keyframe_min_ratio", t.keyframe_min_ratio);
  s.readPositive("keyframe_max_frames", t.keyframe_max_frames);
  s.readPositive("keyframe_translation", t.keyframe_translation);
  s.readPositive("keyframe_rotation_deg", t.keyframe_rotation_deg);
  s.readInRange("keyframe_max_unmapped", t.keyframe_max_unmapped, 0, 1000);
  s.readPositive("max_prediction_error", t.max_prediction_error);
  s.readPositive("pnp_iterations", t.pnp_iterations);
  s.readPositive("pnp_reprojection_px", t.pnp_reprojection_px);
  s.readPositive("pnp_min_matches", t.pnp_min_matches);
  if (t.pnp_min_matches < 4) s.fail("pnp_min_matches", "must be >= 4 (EPnP)");
  s.readPositive("max_velocity_gap_s", t.max_velocity_gap_s);
  s.readPositive("max_camera_speed", t.max_camera_speed);
  s.readPositive("max_point_depth", t.max_point_depth);
  t.pose_solver = readSolverOptions(s.child("pose_solver"), t.pose_solver);
  s.rejectUnknownKeys();
  return t;
}

}  // namespace ply_slam
