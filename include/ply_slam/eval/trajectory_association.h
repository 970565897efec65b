#pragma once

#include <utility>
#include <vector>

#include "ply_slam/common/stamped_pose.h"

namespace ply_slam {

// Pairs (index in a, index in b) of poses whose stamps differ by at most max_dt,
// each pose used once, closest pairs first (TUM associate.py semantics).
std::vector<std::pair<size_t, size_t>> associateByStamp(const Trajectory& a, const Trajectory& b,
                                                        double max_dt = 0.02);

}  // namespace ply_slam
