#pragma once

#include <optional>
#include <utility>
#include <vector>

#include "ply_slam/common/stamped_pose.h"

namespace ply_slam {

// Pairs (index in a, index in b) of poses whose stamps differ by at most max_dt,
// each pose used once, closest pairs first (TUM associate.py semantics).
std::vector<std::pair<size_t, size_t>> associateByStamp(const Trajectory& a, const Trajectory& b,
                                                        double max_dt = 0.02);

// The first two poses (indices, in file order) with the same stamp, if any: such a pose would
// be paired with two ground-truth poses and count twice.
std::optional<std::pair<size_t, size_t>> findRepeatedStamp(const Trajectory& trajectory);

}  // namespace ply_slam
