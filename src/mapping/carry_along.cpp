#include "ply_slam/mapping/carry_along.h"

#include <map>

#include "ply_slam/common/se3_params.h"

namespace ply_slam {

void carryAlong(Map& map, const std::set<const KeyFrame*>& solved,
                const std::vector<std::pair<KeyFrame*, Eigen::Isometry3d>>& before) {
  std::set<long> carried;
  // How each keyframe moved; one made since the solve began follows its parent, else the
  // keyframe made before it.
  std::map<long, Eigen::Isometry3d> moved;
  Eigen::Isometry3d previous = Eigen::Isometry3d::Identity();
  for (const auto& [kf, T_wc] : before) {
    if (!solved.count(kf)) {
      const auto parent = kf->parent ? moved.find(kf->parent->id) : moved.end();
      // Nearest rigid: carried update after update, the drift grew tenfold every few updates.
      kf->T_cw = nearestRigid((parent != moved.end() ? parent->second : previous) * T_wc).inverse();
      carried.insert(kf->id);
    }
    previous = moved[kf->id] = nearestRigid(kf->T_wc() * nearestRigid(T_wc).inverse());
  }
  if (carried.empty()) return;
  for (const auto& point : map.mapPoints()) {
    if (point->bad || !carried.count(point->first_keyframe_id)) continue;
    point->moveBy(moved.at(point->first_keyframe_id));
  }
  for (const auto& line : map.mapLines()) {
    if (line->bad || !carried.count(line->first_keyframe_id)) continue;
    line->moveBy(moved.at(line->first_keyframe_id));
  }
}

}  // namespace ply_slam
