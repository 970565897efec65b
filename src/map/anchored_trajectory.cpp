#include "ply_slam/map/anchored_trajectory.h"

#include <stdexcept>
#include <string>

namespace ply_slam {

void AnchoredTrajectory::add(double stamp, long anchor, const Eigen::Isometry3d& T_anchor_world,
                             const Eigen::Isometry3d& T_camera_world) {
  frames_.push_back({stamp, anchor, T_anchor_world * T_camera_world.inverse()});
}

long AnchoredTrajectory::reanchor(long erased, const Eigen::Isometry3d& T_erased_world,
                                  const KeyFramePoses& live) {
  long anchor = erased;
  for (Frame& f : frames_) {
    if (f.anchor != erased) continue;
    auto before = live.lower_bound(erased);
    if (before == live.begin())
      throw std::invalid_argument("no keyframe before erased keyframe " + std::to_string(erased) +
                                  " to hang its frames from");
    --before;
    anchor = before->first;
    f.T_anchor_camera = before->second * T_erased_world.inverse() * f.T_anchor_camera;
    f.anchor = anchor;
  }
  return anchor;
}

Trajectory AnchoredTrajectory::trajectory(const KeyFramePoses& poses) const {
  Trajectory trajectory;
  trajectory.reserve(frames_.size());
  for (const Frame& f : frames_) {
    const auto pose = poses.find(f.anchor);
    if (pose == poses.end())
      throw std::invalid_argument("no pose for keyframe " + std::to_string(f.anchor) +
                                  ", the anchor of the frame at " + std::to_string(f.stamp));
    trajectory.push_back({f.stamp, pose->second.inverse() * f.T_anchor_camera});
  }
  return trajectory;
}

}  // namespace ply_slam
