#include "ply_slam/dense/voxel_filter.h"

#include <pcl/common/common.h>
#include <pcl/filters/voxel_grid.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>

namespace ply_slam {
namespace {

void filterInto(const DenseCloud& cloud, float leaf, DenseCloud& out) {
  if (cloud.empty()) return;
  pcl::PointXYZRGBL lo, hi;
  pcl::getMinMax3D(cloud, lo, hi);
  // VoxelGrid numbers its voxels with 32-bit ints and leaves a cloud unfiltered when they
  // would overflow (a large map with small voxels): such a cloud is split in two along its
  // longest axis at a voxel boundary (VoxelGrid's voxels are floor(p / leaf), so no voxel is
  // cut) and each half filtered on its own.
  const Eigen::Array3f first = (lo.getArray3fMap() / leaf).floor();
  const Eigen::Array3f cells = (hi.getArray3fMap() / leaf).floor() - first + 1.f;
  const double voxels = double(cells.x()) * cells.y() * cells.z();
  if (voxels > std::numeric_limits<std::int32_t>::max() / 2) {
    int axis = 0;
    cells.maxCoeff(&axis);
    const float split = first[axis] + std::floor(cells[axis] / 2);  // first cell of the upper half
    DenseCloud low, high;
    for (const auto& p : cloud.points)
      (std::floor(p.getArray3fMap()[axis] / leaf) < split ? low : high).push_back(p);
    if (low.empty() || high.empty()) {  // float rounding at huge coordinates: cannot split
      out += cloud;
      return;
    }
    filterInto(low, leaf, out);
    filterInto(high, leaf, out);
    return;
  }
  // VoxelGrid wants a shared pointer to its input; alias the cloud without owning it.
  const DenseCloud::ConstPtr input(DenseCloud::ConstPtr(), &cloud);
  pcl::VoxelGrid<pcl::PointXYZRGBL> grid;
  grid.setInputCloud(input);
  grid.setLeafSize(leaf, leaf, leaf);
  grid.setDownsampleAllData(true);  // colour averaged, label by majority
  DenseCloud filtered;
  grid.filter(filtered);
  out += filtered;
}

}  // namespace

DenseCloudPtr voxelFilter(const DenseCloud& cloud, double leaf) {
  if (!(leaf > 0.0)) throw std::invalid_argument("voxelFilter: leaf size must be > 0");
  auto out = std::make_shared<DenseCloud>();
  // A NaN or infinite point has no voxel (and would make the split above recurse for ever).
  const auto finite = [](const pcl::PointXYZRGBL& p) { return p.getArray3fMap().allFinite(); };
  if (std::all_of(cloud.begin(), cloud.end(), finite)) {
    filterInto(cloud, static_cast<float>(leaf), *out);
    return out;
  }
  DenseCloud finite_points;
  for (const auto& p : cloud.points)
    if (finite(p)) finite_points.push_back(p);
  filterInto(finite_points, static_cast<float>(leaf), *out);
  return out;
}

}  // namespace ply_slam
