#pragma once

#include <Eigen/Geometry>
#include <map>
#include <vector>

#include "ply_slam/common/stamped_pose.h"

namespace ply_slam {

// Tracked camera poses, each kept relative to a keyframe (its anchor) as it was when tracked, so
// that the trajectory moves with the map when bundle adjustment or a loop closure moves the
// keyframes. Used by System (the tracker's frames) and mapping_node (the poses it receives).
class AnchoredTrajectory {
 public:
  // Keyframe id -> T_cw (world to keyframe camera) as the map has it now.
  using KeyFramePoses = std::map<long, Eigen::Isometry3d>;

  // A frame tracked at T_camera_world while its anchor was at T_anchor_world.
  void add(double stamp, long anchor, const Eigen::Isometry3d& T_anchor_world,
           const Eigen::Isometry3d& T_camera_world);
  // The anchor `erased` left the map (last at T_erased_world): its frames, where they are, hang
  // from the keyframe in `live` with the largest id below it (the same stretch of the path);
  // returns that id, or `erased` when no frame hung from it. Throws std::invalid_argument when
  // frames hang from it and `live` has no keyframe before it.
  long reanchor(long erased, const Eigen::Isometry3d& T_erased_world, const KeyFramePoses& live);
  // Every frame placed from its anchor's pose in `poses` (which must hold every anchor).
  Trajectory trajectory(const KeyFramePoses& poses) const;
  size_t size() const { return frames_.size(); }

 private:
  struct Frame {
    double stamp = 0.0;
    long anchor = 0;
    Eigen::Isometry3d T_anchor_camera = Eigen::Isometry3d::Identity();
  };
  std::vector<Frame> frames_;
};

}  // namespace ply_slam
