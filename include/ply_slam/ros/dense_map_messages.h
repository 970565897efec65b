#pragma once

#include <sensor_msgs/PointCloud2.h>
#include <std_msgs/Header.h>
#include <visualization_msgs/MarkerArray.h>

#include <vector>

#include "ply_slam/dense/key_frame_cloud.h"
#include "ply_slam/dense/semantic_octree.h"

namespace ply_slam {

// The dense maps as ROS messages: the global cloud with fields x y z rgb label
// (label = COCO class id + 1, 0 = unknown), the occupied octree voxels as one CUBE_LIST per
// colour, and their centres as a cloud with x y z rgb.
sensor_msgs::PointCloud2 toDenseCloudMsg(const DenseCloud& cloud, const std_msgs::Header& header);
visualization_msgs::MarkerArray toVoxelMarkers(const std::vector<SemanticOctree::Voxel>& voxels,
                                               const std_msgs::Header& header);
sensor_msgs::PointCloud2 toVoxelCloudMsg(const std::vector<SemanticOctree::Voxel>& voxels,
                                         const std_msgs::Header& header);

}  // namespace ply_slam
