#include "ply_slam/dense/voxel_filter.h"

#include <pcl/filters/voxel_grid.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <stdexcept>

namespace ply_slam {

DenseCloudPtr voxelFilter(const DenseCloud& cloud, double leaf) {
  if (!(leaf > 0.0)) throw std::invalid_argument("voxelFilter: leaf size must be > 0");
  auto out = std::make_shared<DenseCloud>();
  if (cloud.empty()) return out;
  // VoxelGrid wants a shared pointer to its input; alias the caller's cloud without owning it.
  const DenseCloud::ConstPtr input(DenseCloud::ConstPtr(), &cloud);
  pcl::VoxelGrid<pcl::PointXYZRGBL> grid;
  grid.setInputCloud(input);
  grid.setLeafSize(static_cast<float>(leaf), static_cast<float>(leaf), static_cast<float>(leaf));
  grid.setDownsampleAllData(true);  // colour averaged, label by majority
  grid.filter(*out);
  return out;
}

}  // namespace ply_slam
