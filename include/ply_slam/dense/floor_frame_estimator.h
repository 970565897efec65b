#pragma once

#include <Eigen/Core>
#include <vector>

#include "ply_slam/common/stamped_pose.h"
#include "ply_slam/dense/occupancy_grid.h"
#include "ply_slam/dense/occupancy_grid_options.h"

namespace ply_slam {

// Finds the floor in the SLAM world, whose frame is the first camera's and knows nothing of
// gravity. With floor "auto": the cameras' mean -y axis (a hand-held or robot camera is held
// roughly upright) only guesses up, within the camera's pitch; the floor is the lowest large
// plane of occupied voxels below every camera centre whose normal lies within 30 deg of that
// guess (RANSAC, least-squares refits; a plane under the one with the most voxels wins with a
// quarter of its voxels: a desk top seen from above), so a tilted camera gives a level grid.
// Without such a plane (no floor seen): the guessed up and the lowest voxels' height.
class FloorFrameEstimator {
 public:
  explicit FloorFrameEstimator(const OccupancyGridOptions& options);

  // `points`: where the occupied voxels of static things hold their surface (SLAM world),
  // `voxel_size` their edge; `trajectory`: camera poses (the first places the frame).
  FloorFrame estimate(const std::vector<Eigen::Vector3d>& points, double voxel_size,
                      const Trajectory& trajectory) const;

  // The frame on the plane up . p = height: origin under the first camera, x along its view.
  static Eigen::Isometry3d frameOn(const Eigen::Vector3d& up, double height,
                                   const Trajectory& trajectory);

 private:
  OccupancyGridOptions options_;
};

}  // namespace ply_slam
