#include "ply_slam/mapping/carry_along.h"

#include <map>

namespace ply_slam {
namespace {

// The rigid transform nearest T: the composed moves of a keyframe carried update after update
// would otherwise drift off the rotations, and Isometry3d's inverse (a transpose) feeds the drift
// back into the next move (it grew tenfold per few updates with the tracker following late).
Eigen::Isometry3d rigid(const Eigen::Isometry3d& T) {
  Eigen::Isometry3d out = T;
  out.linear() = Eigen::Quaterniond(T.linear()).normalized().toRotationMatrix();
  return out;
}

}  // namespace

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
      kf->T_cw = rigid((parent != moved.end() ? parent->second : previous) * T_wc).inverse();
      carried.insert(kf->id);
    }
    previous = moved[kf->id] = rigid(kf->T_wc() * rigid(T_wc).inverse());
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
