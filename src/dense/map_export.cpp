#include "ply_slam/dense/map_export.h"

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <filesystem>
#include <set>
#include <stdexcept>

#include "ply_slam/dense/cloud_files.h"
#include "ply_slam/io/file_writes.h"

namespace ply_slam {

void writeDenseMaps(const std::string& folder, DenseMap& dense, const SemanticOctree& octree) {
  namespace fs = std::filesystem;
  fs::create_directories(folder);
  const fs::path dir(folder);
  FileWrites files;

  const DenseCloudPtr cloud = dense.globalCloud();
  // PCL refuses to write an empty cloud; an empty map is still a valid (empty) result.
  DenseCloud to_write = *cloud;
  to_write.width = static_cast<std::uint32_t>(to_write.size());
  to_write.height = 1;
  if (!to_write.empty()) {
    files.attempt([&] { writeCloudPcd((dir / "dense_map.pcd").string(), to_write); });
    files.attempt([&] { writeCloudPly((dir / "dense_map.ply").string(), to_write); });
  }

  const std::string ot = (dir / "semantic_octree.ot").string();
  files.attempt([&] { octree.writeColourTree(ot); });
  const std::string bt = (dir / "octree.bt").string();
  files.attempt([&] { octree.writeBinaryTree(bt); });

  std::set<std::uint32_t> labels{ClassPalette::kUnknown};
  for (const auto& p : cloud->points) labels.insert(p.label);
  for (const auto& v : octree.occupiedVoxels()) labels.insert(v.label);
  const std::string legend = (dir / "map_legend.txt").string();
  files.attempt([&] { octree.palette().writeLegend(legend, {labels.begin(), labels.end()}); });
  files.throwFailures();
}

}  // namespace ply_slam
