#pragma once

#include <string>

#include "ply_slam/common/stamped_pose.h"

namespace ply_slam {

// Writes a PNG with a top view (x-y) and a side view (x-z) of the ground truth and of the
// estimate (already aligned to the ground truth), equal axis scales, a metre grid, a legend
// and `title` on top. gt may be empty.
void writeTrajectoryPlot(const std::string& png_path, const Trajectory& gt,
                         const Trajectory& est_aligned, const std::string& title);

}  // namespace ply_slam
