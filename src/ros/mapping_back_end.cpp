#include "ply_slam/ros/mapping_back_end.h"

namespace ply_slam {

MappingBackEnd MappingBackEnd::fromConfig(const SystemConfig& config) {
  MappingBackEnd back_end;
  if (!config.dense.enabled) return back_end;
  back_end.dense = std::make_unique<DenseMappingWorker>(config.dense);
  if (!config.grid.enabled) return back_end;
  // The grid leaves out the classes that move, by the octree's own labels.
  back_end.dense->withMaps([&](DenseMap&, const SemanticOctree& octree) {
    back_end.grid_builder = std::make_unique<OccupancyGridBuilder>(
        config.grid,
        OccupancyGridBuilder::labelsOf(octree.palette(), config.dynamic.active_classes));
  });
  return back_end;
}

}  // namespace ply_slam
