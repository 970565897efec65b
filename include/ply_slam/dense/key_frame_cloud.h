#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <memory>
#include <vector>

// PCL stays out of this widely included header: the cloud types are only declared here.
namespace pcl {
struct PointXYZRGBL;
template <typename PointT>
class PointCloud;
}  // namespace pcl

namespace ply_slam {

// Points of the dense maps: position (m), colour, and a ClassPalette label.
using DenseCloud = pcl::PointCloud<pcl::PointXYZRGBL>;
using DenseCloudPtr = std::shared_ptr<DenseCloud>;

// The dense cloud of one keyframe, in its camera frame, and the pose that places it.
struct KeyFrameCloud {
  long id = 0;
  Eigen::Isometry3d T_wc = Eigen::Isometry3d::Identity();
  DenseCloudPtr points;
  // Camera-frame points beyond the map's max_depth (up to the camera's): too noisy to map,
  // but the space in front of them is free. The octree clears along these rays.
  std::vector<Eigen::Vector3f> clearing_rays;
  // Evaluation only (may be null): the same points, label = 1 where the source pixel was
  // marked in the builder's tag mask (e.g. ground-truth walker masks), else 0.
  DenseCloudPtr tags;
};

}  // namespace ply_slam
