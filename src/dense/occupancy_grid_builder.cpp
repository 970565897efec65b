#include "ply_slam/dense/occupancy_grid_builder.h"

#include <octomap/ColorOcTree.h>

#include <algorithm>
#include <cmath>

#include "ply_slam/dense/floor_frame_estimator.h"

namespace ply_slam {
namespace {

// Calls f with the centre of every finest voxel of the octree's leaves that are in `state`
// (a pruned leaf stands for several finest voxels).
template <typename F>
void forEachLeafVoxel(const octomap::ColorOcTree& tree, bool occupied, F f) {
  const double finest = tree.getResolution();
  for (auto it = tree.begin_leafs(), end = tree.end_leafs(); it != end; ++it) {
    if (tree.isNodeOccupied(*it) != occupied) continue;
    const octomap::point3d c = it.getCoordinate();
    const int n = std::max(1, static_cast<int>(std::lround(it.getSize() / finest)));
    const double first = -0.5 * (n - 1) * finest;
    for (int a = 0; a < n; ++a)
      for (int b = 0; b < n; ++b)
        for (int k = 0; k < n; ++k)
          f(Eigen::Vector3d(c.x() + first + a * finest, c.y() + first + b * finest,
                            c.z() + first + k * finest));
  }
}

}  // namespace

OccupancyGridBuilder::OccupancyGridBuilder(const OccupancyGridOptions& options,
                                           std::set<std::uint32_t> moving_labels)
    : options_(options), moving_labels_(std::move(moving_labels)) {}

std::set<std::uint32_t> OccupancyGridBuilder::labelsOf(const ClassPalette& palette,
                                                       const std::vector<std::string>& classes) {
  std::set<std::uint32_t> labels;
  for (const auto& name : classes) {
    const std::uint32_t label = palette.label(name);
    if (label != ClassPalette::kUnknown) labels.insert(label);
  }
  return labels;
}

OccupancyGrid OccupancyGridBuilder::build(const SemanticOctree& octree,
                                          const Trajectory& trajectory) const {
  const std::vector<SemanticOctree::Voxel> voxels = octree.occupiedVoxels();
  std::vector<Eigen::Vector3d> static_points;
  double voxel_size = options_.resolution;
  for (const auto& v : voxels)
    if (!moving(v.label)) {
      static_points.push_back(v.surface);
      voxel_size = v.size;
    }
  return build(octree, voxels,
               FloorFrameEstimator(options_).estimate(static_points, voxel_size, trajectory));
}

OccupancyGrid OccupancyGridBuilder::build(const SemanticOctree& octree,
                                          const FloorFrame& floor) const {
  return build(octree, octree.occupiedVoxels(), floor);
}

OccupancyGrid OccupancyGridBuilder::build(const SemanticOctree& octree,
                                          const std::vector<SemanticOctree::Voxel>& voxels,
                                          const FloorFrame& floor) const {
  const Eigen::Isometry3d T_floor_world = floor.T_world_floor.inverse();
  // Floor-frame xy of the voxels that decide cells: occupied ones in the band (where their
  // surface lies: with voxels as large as cells, the centre would often name the cell beside),
  // free ones between the floor and the robot's top.
  std::vector<Eigen::Vector2d> occupied, free;
  for (const auto& v : voxels) {
    if (moving(v.label)) continue;
    const Eigen::Vector3d p = T_floor_world * v.surface;
    if (p.z() >= options_.floor_clearance && p.z() <= options_.robot_height)
      occupied.push_back(p.head<2>());
  }
  forEachLeafVoxel(octree.tree(), false, [&](const Eigen::Vector3d& centre) {
    const Eigen::Vector3d p = T_floor_world * centre;
    if (p.z() > 0.0 && p.z() <= options_.robot_height) free.push_back(p.head<2>());
  });

  // Extent, snapped to whole cells of the floor frame so that cells keep their place when the
  // map grows.
  const double res = options_.resolution;
  Eigen::Vector2d lo(0, 0), hi(0, 0);
  bool any = false;
  for (const auto* points : {&occupied, &free})
    for (const auto& p : *points) {
      lo = any ? Eigen::Vector2d(lo.cwiseMin(p)) : p;
      hi = any ? Eigen::Vector2d(hi.cwiseMax(p)) : p;
      any = true;
    }
  const Eigen::Vector2d origin = (lo / res).array().floor().matrix() * res;
  const int width = any ? static_cast<int>(std::floor((hi.x() - origin.x()) / res)) + 1 : 0;
  const int height = any ? static_cast<int>(std::floor((hi.y() - origin.y()) / res)) + 1 : 0;
  OccupancyGrid grid(width, height, res, origin, floor);
  int i = 0, j = 0;
  for (const auto& p : free)
    if (grid.cellOf(p, &i, &j)) grid.set(i, j, OccupancyGrid::kFree);
  for (const auto& p : occupied)
    if (grid.cellOf(p, &i, &j)) grid.set(i, j, OccupancyGrid::kOccupied);
  return grid;
}

}  // namespace ply_slam
