#pragma once

#include <string>

#include "ply_slam/dense/dense_map.h"
#include "ply_slam/dense/semantic_octree.h"

namespace ply_slam {

// Writes the maps into `folder` (created if missing): dense_map.pcd and dense_map.ply (x y z,
// rgb, label), semantic_octree.ot (ColorOcTree, opens in octovis), octree.bt (occupancy only)
// and map_legend.txt (the classes in the maps, with their colours). Every file is tried; then
// std::runtime_error names each that could not be written.
void writeDenseMaps(const std::string& folder, DenseMap& dense, const SemanticOctree& octree);

}  // namespace ply_slam
