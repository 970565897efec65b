#pragma once

#include <Eigen/Geometry>
#include <set>
#include <utility>
#include <vector>

#include "ply_slam/map/map.h"

namespace ply_slam {

// After a solution (global bundle adjustment, a loop's pose graph; in the tracker's copy any
// update of the mapping side) was written into the map: the keyframes the tracker made
// meanwhile (not in `solved`) move as their spanning-tree parent moved, else as the keyframe
// made before them, and the landmarks they created move with them. `before`: every keyframe's
// T_wc before the solution was written, in id order. Map's lock held.
void carryAlong(Map& map, const std::set<const KeyFrame*>& solved,
                const std::vector<std::pair<KeyFrame*, Eigen::Isometry3d>>& before);

}  // namespace ply_slam
