#include "ply_slam/ros/mapping_back_end.h"

#include <filesystem>

#include "ply_slam/features/orb_extractor.h"
#include "ply_slam/system/system.h"

namespace ply_slam {

std::unique_ptr<MappingSide> MappingBackEnd::makeMappingSide(const SystemConfig& config) {
  // On its own thread, as tracking_node's thread: a global BA is solved beside the keyframes.
  return std::make_unique<MappingSide>(config, true, false);
}

MappingBackEnd MappingBackEnd::fromOptions(const MappingNodeOptions& options) {
  const SystemConfig& config = options.config;
  MappingBackEnd back_end;
  if (options.map_keyframes) {
    back_end.mapping = makeMappingSide(config);
    back_end.orb_scales =
        std::make_shared<const std::vector<double>>(OrbExtractor(config.orb).scales());
    // The tracker apart loads the same file into its copy; each job says which it loaded.
    if (!options.map.empty())
      back_end.mapping->loadMap(
          (std::filesystem::path(options.map) / System::kMapFileName).string(),
          back_end.orb_scales.get());
  }
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
