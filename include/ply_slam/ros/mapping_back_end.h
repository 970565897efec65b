#pragma once

#include <memory>

#include "ply_slam/common/config.h"
#include "ply_slam/dense/dense_mapping_worker.h"
#include "ply_slam/dense/occupancy_grid_builder.h"
#include "ply_slam/system/mapping_side.h"

namespace ply_slam {

// What mapping_node builds its maps with beyond the sparse copy of the tracker's map: the dense
// cloud and semantic octree on their own thread, and the occupancy grid from the octree. Built
// by its main from the config and handed to the node.
struct MappingBackEnd {
  std::unique_ptr<DenseMappingWorker> dense;           // null: dense.enabled is false
  std::unique_ptr<OccupancyGridBuilder> grid_builder;  // null: no dense maps or grid.enabled false
  // ~map_keyframes: the mapping side, and the ORB pyramid's scale per level its keyframes use.
  std::unique_ptr<MappingSide> mapping;
  std::vector<double> orb_scales;

  // Throws std::runtime_error naming a vocabulary that does not load (map_keyframes, loop on).
  static MappingBackEnd fromConfig(const SystemConfig& config, bool map_keyframes = false);
};

}  // namespace ply_slam
