#pragma once

#include <string>

#include "ply_slam/map/map_file_contents.h"

namespace ply_slam {

// A map file whose checksum holds can still carry numbers no map has (a writer's bug, a file
// edited or made by hand): a NaN keyframe pose made every frame tracked in it NaN, with
// "lost 0". Checked as strictly as a config: every number finite, coordinates within
// +-kMaxCoordinate m, rotations rotations, depths, distances and weights not negative.
// Empty when the map is usable, else the first fault, naming the keyframe, point or line.
std::string findMapValueProblem(const MapFileContents& map);

constexpr double kMaxMapCoordinate = 1e9;  // m; as ply_slam_eval's bound on a trajectory

}  // namespace ply_slam
