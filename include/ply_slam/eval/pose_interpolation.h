#pragma once

#include <Eigen/Geometry>
#include <optional>

#include "ply_slam/common/stamped_pose.h"

namespace ply_slam {

// The pose of a time-ordered trajectory at `stamp`: translation linear and rotation slerp
// between the two poses around it; none when they are more than `max_gap` s apart or the
// stamp is outside (a stamp equal to the first pose's gives that pose).
std::optional<Eigen::Isometry3d> interpolatePose(const Trajectory& trajectory, double stamp,
                                                 double max_gap);

}  // namespace ply_slam
