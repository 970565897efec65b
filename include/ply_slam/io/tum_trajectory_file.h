#pragma once

#include <string>

#include "ply_slam/common/stamped_pose.h"

namespace ply_slam {

// TUM trajectory format: "stamp tx ty tz qx qy qz qw" per line, '#' comments.
// Throws std::runtime_error naming the file and line on a malformed entry.
Trajectory readTumTrajectory(const std::string& path);
// Writes with full stamp precision (6 decimals) and 7 significant pose decimals.
void writeTumTrajectory(const std::string& path, const Trajectory& trajectory);

}  // namespace ply_slam
