#include "ply_slam/mapping/loop_correction_options_yaml.h"

#include "ply_slam/common/solver_options_yaml.h"

namespace ply_slam {

LoopCorrectionOptions readLoopCorrectionOptions(ConfigSection section) {
  LoopCorrectionOptions o;
  section.readInRange("strong_covisibility", o.strong_covisibility, 1, 1000000);
  section.readInRange("loop_side_keyframes", o.loop_side_keyframes, 0, 1000);
  section.readInRange("max_drift_fraction", o.max_drift_fraction, 0.0, 10.0);
  section.readInRange("max_drift_floor_m", o.max_drift_floor_m, 0.0, 1000.0);
  section.readInRange("max_rotation_drift_deg_per_m", o.max_rotation_drift_deg_per_m, 0.0, 360.0);
  section.readInRange("max_rotation_drift_floor_deg", o.max_rotation_drift_floor_deg, 0.0, 360.0);
  section.readInRange("min_keyframes_between", o.min_keyframes_between, 0, 1000000);
  section.readInRange("pose_graph_iterations", o.pose_graph.max_iterations, 1, 10000);
  section.readInRange("pose_graph_rotation_sigma_rad", o.pose_graph.rotation_sigma_rad, 1e-9, 10.0);
  section.readInRange("pose_graph_translation_sigma_m", o.pose_graph.translation_sigma_m, 1e-9,
                      100.0);
  readLinearSolver(section, "pose_graph_linear_solver", o.pose_graph.linear_solver);
  section.readInRange("global_ba_iterations", o.global_ba_iterations, 0, 10000);
  section.rejectUnknownKeys();
  return o;
}

}  // namespace ply_slam
