#include "ply_slam/mapping/culling_options_yaml.h"

namespace ply_slam {

CullingOptions readCullingOptions(ConfigSection section) {
  CullingOptions o;
  KeyFrameCullerOptions& k = o.keyframes;
  // 1.0: "more than all its landmarks" never holds, so no keyframe is culled.
  section.readInRange("keyframe_redundancy", k.redundancy, 0.5, 1.0);
  section.readInRange("keyframe_min_observers", k.min_observers, 1, 100);
  section.readInRange("keyframe_level_slack", k.level_slack, 0, 10);
  section.readInRange("keyframe_min_point_observers", k.min_point_observers, 1, 100);
  MapPointCullerOptions& p = o.points;
  section.readInRange("point_min_found_ratio", p.min_found_ratio, 0.0, 1.0);
  section.readInRange("point_min_visible", p.min_visible, 1, 1000000);
  section.readInRange("point_probation_keyframes", p.probation_keyframes, 1, 1000);
  section.readInRange("point_min_keyframe_observers", p.min_keyframe_observers, 1, 100);
  section.rejectUnknownKeys();
  return o;
}

}  // namespace ply_slam
