#pragma once

#include <cstdint>
#include <set>
#include <string>
#include <vector>

#include "ply_slam/common/stamped_pose.h"
#include "ply_slam/dense/class_palette.h"
#include "ply_slam/dense/occupancy_grid.h"
#include "ply_slam/dense/occupancy_grid_options.h"
#include "ply_slam/dense/semantic_octree.h"

namespace ply_slam {

// The semantic octree flattened into a 2D occupancy grid for a ground robot. Heights are taken
// from the floor (FloorFrameEstimator). A cell is
// - occupied where an occupied voxel whose majority class is not a moving one (people and the
//   other classes in `moving_labels`) has its surface (the mean of its hits) in
//   [floor_clearance, robot_height];
// - free where, with nothing occupied, a free voxel (rays passed) has its centre between the
//   floor and robot_height: a camera on a robot sees the floor along rays that stay below the
//   clearance, and a ray that reached the floor there crossed the whole band;
// - unknown elsewhere.
class OccupancyGridBuilder {
 public:
  OccupancyGridBuilder(const OccupancyGridOptions& options, std::set<std::uint32_t> moving_labels);

  // The palette's labels of the named classes (e.g. dynamic.active_classes); unknown names are
  // left out.
  static std::set<std::uint32_t> labelsOf(const ClassPalette& palette,
                                          const std::vector<std::string>& classes);

  // Finds the floor (options' floor: auto or given), then builds the grid on it.
  OccupancyGrid build(const SemanticOctree& octree, const Trajectory& trajectory) const;
  // On a known floor frame (T_world_floor: z up, z = 0 on the floor).
  OccupancyGrid build(const SemanticOctree& octree, const FloorFrame& floor) const;

 private:
  bool moving(std::uint32_t label) const { return moving_labels_.count(label) > 0; }
  // `voxels`: the octree's occupied ones, taken once by the caller.
  OccupancyGrid build(const SemanticOctree& octree,
                      const std::vector<SemanticOctree::Voxel>& voxels,
                      const FloorFrame& floor) const;

  OccupancyGridOptions options_;
  std::set<std::uint32_t> moving_labels_;
};

}  // namespace ply_slam
