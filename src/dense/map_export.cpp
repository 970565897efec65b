#include "ply_slam/dense/map_export.h"

#include <pcl/io/pcd_io.h>
#include <pcl/io/ply_io.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <filesystem>
#include <set>
#include <stdexcept>

#include "ply_slam/io/atomic_file.h"

namespace ply_slam {

std::vector<std::string> writeDenseMaps(const std::string& folder, DenseMap& dense,
                                        const SemanticOctree& octree) {
  namespace fs = std::filesystem;
  fs::create_directories(folder);
  const fs::path dir(folder);
  std::vector<std::string> written;

  const DenseCloudPtr cloud = dense.globalCloud();
  const std::string pcd = (dir / "dense_map.pcd").string();
  const std::string ply = (dir / "dense_map.ply").string();
  // PCL refuses to write an empty cloud; an empty map is still a valid (empty) result.
  DenseCloud to_write = *cloud;
  to_write.width = static_cast<std::uint32_t>(to_write.size());
  to_write.height = 1;
  if (!to_write.empty()) {
    writeFileAtomically(pcd, [&](const std::string& temp) {
      return pcl::io::savePCDFileBinary(temp, to_write) == 0;
    });
    writeFileAtomically(ply, [&](const std::string& temp) {
      return pcl::io::savePLYFileBinary(temp, to_write) == 0;
    });
    written.push_back(pcd);
    written.push_back(ply);
  }

  const std::string ot = (dir / "semantic_octree.ot").string();
  const std::string bt = (dir / "octree.bt").string();
  octree.writeColourTree(ot);
  octree.writeBinaryTree(bt);
  written.push_back(ot);
  written.push_back(bt);

  std::set<std::uint32_t> labels{ClassPalette::kUnknown};
  for (const auto& p : cloud->points) labels.insert(p.label);
  for (const auto& v : octree.occupiedVoxels()) labels.insert(v.label);
  const std::string legend = (dir / "map_legend.txt").string();
  octree.palette().writeLegend(legend, {labels.begin(), labels.end()});
  written.push_back(legend);
  return written;
}

}  // namespace ply_slam
