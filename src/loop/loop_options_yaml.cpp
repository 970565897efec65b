#include "ply_slam/loop/loop_options_yaml.h"

namespace ply_slam {
namespace {

constexpr double kHuge = 1e12;

void readGeneralKeys(ConfigSection& s, LoopOptions& o) {
  s.read("enabled", o.enabled);
  s.read("orb_vocabulary", o.orb_vocabulary);
  s.read("lbd_vocabulary", o.lbd_vocabulary);
}

void readInstanceKeys(ConfigSection& s, LoopOptions& o) {
  s.readInRange("position_weight", o.position_weight, 0.0, 1.0);
  s.readInRange("iou_weight", o.iou_weight, 0.0, 1.0);
  s.readInRange("iou_epsilon", o.iou_epsilon, 0.0, 1.0);
  s.readInRange("spatial_consistency_threshold", o.spatial_consistency_threshold, 0.0, 1.0);
  s.readInRange("consistency_boost", o.consistency_boost, 0.0, 1.0);
  s.readInRange("consistency_penalty", o.consistency_penalty, 0.0, 1.0);
  s.readInRange("sure_position", o.sure_position, 0.0, 1.0);
  s.readInRange("dyna_ceiling", o.dyna_ceiling, 0.0, 1.0);
  s.readInRange("dyna_floor", o.dyna_floor, 0.0, 1.0);
  s.readInRange("dyna_step", o.dyna_step, 0.0, 1.0);
  s.readList("dynamic_classes", o.dynamic_classes);
}

void readSelectionKeys(ConfigSection& s, LoopOptions& o) {
  s.readInRange("point_line_weight", o.point_line_weight, 0.0, 1.0);
  s.readInRange("instance_weight", o.instance_weight, 0.0, 1.0);
  s.readInRange("min_normalised_score", o.min_normalised_score, 0.0, kHuge);
  s.readInRange("consistency", o.consistency, 1, 1000);
  s.readInRange("min_covisible_shared", o.min_covisible_shared, 1, 1000000);
  s.readInRange("min_candidate_age_s", o.min_candidate_age_s, 0.0, kHuge);
}

void readGeometricKeys(ConfigSection& s, LoopOptions& o) {
  s.readInRange("direct_index_levels_up", o.direct_index_levels_up, 0, 20);
  s.readInRange("match_max_distance", o.match_max_distance, 0, 256);
  s.readInRange("match_ratio", o.match_ratio, 0.0, 1.0);
  s.readInRange("ransac_iterations", o.ransac_iterations, 1, 1000000);
  s.readInRange("ransac_seed", o.ransac_seed, 0u, ~0u);
  s.readInRange("refine_iterations", o.refine_iterations, 0, 1000);
  s.readInRange("inlier_sigma_factor", o.inlier_sigma_factor, 0.0, kHuge);
  s.readInRange("min_inlier_distance", o.min_inlier_distance, 0.0, kHuge);
  s.readInRange("min_inliers_3d", o.min_inliers_3d, 3, 1000000);
  s.readInRange("reprojection_px", o.reprojection_px, 0.0, kHuge);
  s.readInRange("min_reprojection_inliers", o.min_reprojection_inliers, 0, 1000000);
  s.readInRange("max_revisit_distance_m", o.max_revisit_distance_m, 0.0, kHuge);
  s.readInRange("max_revisit_angle_deg", o.max_revisit_angle_deg, 0.0, 180.0);
}

}  // namespace

LoopOptions readLoopOptions(ConfigSection section) {
  LoopOptions options;
  readGeneralKeys(section, options);
  readInstanceKeys(section, options);
  readSelectionKeys(section, options);
  readGeometricKeys(section, options);
  section.rejectUnknownKeys();
  if (options.dyna_floor > options.dyna_ceiling) {
    section.fail("dyna_floor", "must not exceed loop.dyna_ceiling");
  }
  return options;
}

LoopOptions loopOptionsFromYaml(const YAML::Node& loop_section) {
  return readLoopOptions(ConfigSection(loop_section, "", "loop"));
}

}  // namespace ply_slam
