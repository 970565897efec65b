#include "ply_slam/map/landmark_values.h"

namespace ply_slam {

MapUpdate::KeyFramePose valuesOf(const KeyFrame& keyframe) {
  return {keyframe.id, keyframe.T_cw, keyframe.parent ? keyframe.parent->id : -1};
}

LandmarkPoint valuesOf(const MapPoint& point) {
  return {point.id, point.position, point.normal, point.position_weight};
}

LandmarkLine valuesOf(const MapLine& line) {
  return {line.id, line.start, line.end, line.start_weight, line.end_weight};
}

void setValues(MapPoint& point, const LandmarkPoint& values) {
  point.position = values.position;
  point.normal = values.normal;
  point.position_weight = values.position_weight;
}

void setValues(MapLine& line, const LandmarkLine& values) {
  line.start = values.start;
  line.end = values.end;
  line.start_weight = values.start_weight;
  line.end_weight = values.end_weight;
}

}  // namespace ply_slam
