#pragma once

#include "ply_slam/map/key_frame.h"
#include "ply_slam/map/key_frame_packet.h"

namespace ply_slam {

// What a copy of the map needs of a keyframe or landmark the mapping side may have changed
// (MapUpdate's values), and setting them on the copy's own (Map::apply).
MapUpdate::KeyFramePose valuesOf(const KeyFrame& keyframe);
LandmarkPoint valuesOf(const MapPoint& point);
LandmarkLine valuesOf(const MapLine& line);
void setValues(MapPoint& point, const LandmarkPoint& values);
void setValues(MapLine& line, const LandmarkLine& values);

}  // namespace ply_slam
