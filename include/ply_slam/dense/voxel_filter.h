#pragma once

#include "ply_slam/dense/key_frame_cloud.h"

namespace ply_slam {

// pcl::VoxelGrid with cubic voxels of `leaf` m: one point per occupied voxel, at the centroid
// of its points, with their mean colour and their most frequent label.
DenseCloudPtr voxelFilter(const DenseCloud& cloud, double leaf);

}  // namespace ply_slam
