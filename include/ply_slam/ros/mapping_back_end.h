#pragma once

#include <memory>

#include "ply_slam/dense/dense_mapping_worker.h"
#include "ply_slam/dense/occupancy_grid_builder.h"
#include "ply_slam/ros/mapping_node_options.h"
#include "ply_slam/system/mapping_side.h"
#include "ply_slam/system/system_config.h"

namespace ply_slam {

// What mapping_node builds its maps with beyond the sparse copy of the tracker's map: the dense
// cloud and semantic octree on their own thread, and the occupancy grid from the octree. Built
// by its main from the config and handed to the node.
struct MappingBackEnd {
  std::unique_ptr<DenseMappingWorker> dense;           // null: dense.enabled is false
  std::unique_ptr<OccupancyGridBuilder> grid_builder;  // null: no dense maps or grid.enabled false
  // ~map_keyframes: the ORB pyramid's scale per level its keyframes point to (on the heap: the
  // back end moves, they must not), and the mapping side (with ~map the saved map loaded).
  std::shared_ptr<const std::vector<double>> orb_scales;
  std::unique_ptr<MappingSide> mapping;

  // Throws std::runtime_error naming a vocabulary that does not load (map_keyframes, loop on) or
  // a map file that does not (map_keyframes with ~map), with the fault.
  static MappingBackEnd fromOptions(const MappingNodeOptions& options);
  // The mapping side as mapping_node runs it, with the map file in `map_folder` loaded ("": an
  // empty map; its keyframes point to `orb_scales`); throws as fromOptions.
  static std::unique_ptr<MappingSide> makeMappingSide(const SystemConfig& config,
                                                      const std::string& map_folder,
                                                      const std::vector<double>* orb_scales);
  // The ORB pyramid's scale per level, on the heap.
  static std::shared_ptr<const std::vector<double>> orbScales(const OrbOptions& orb);
};

}  // namespace ply_slam
