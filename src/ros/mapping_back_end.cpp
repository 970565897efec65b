#include "ply_slam/ros/mapping_back_end.h"

#include <filesystem>

#include "ply_slam/features/orb_extractor.h"
#include "ply_slam/system/system.h"

namespace ply_slam {

std::unique_ptr<MappingSide> MappingBackEnd::makeMappingSide(
    const SystemConfig& config, const std::string& map_folder,
    const std::vector<double>* orb_scales) {
  // On its own thread, as tracking_node's thread: a global BA is solved beside the keyframes.
  auto mapping = std::make_unique<MappingSide>(config, true, false);
  // The tracker apart loads the same file into its copy; each job says which it loaded.
  if (!map_folder.empty())
    mapping->loadMap((std::filesystem::path(map_folder) / System::kMapFileName).string(),
                     orb_scales);
  return mapping;
}

std::shared_ptr<const std::vector<double>> MappingBackEnd::orbScales(const OrbOptions& orb) {
  return std::make_shared<const std::vector<double>>(OrbExtractor(orb).scales());
}

MappingBackEnd MappingBackEnd::fromOptions(const MappingNodeOptions& options) {
  const SystemConfig& config = options.config;
  MappingBackEnd back_end;
  if (options.map_keyframes) {
    back_end.orb_scales = orbScales(config.orb);
    back_end.mapping = makeMappingSide(config, options.map, back_end.orb_scales.get());
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
