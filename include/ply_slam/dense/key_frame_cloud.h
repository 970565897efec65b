#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <memory>

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
  double stamp = 0.0;
  Eigen::Isometry3d T_wc = Eigen::Isometry3d::Identity();
  DenseCloudPtr points;
  // Evaluation only (may be null): the same points, label = 1 where the source pixel was
  // marked in the builder's tag mask (e.g. ground-truth walker masks), else 0.
  DenseCloudPtr tags;
};

}  // namespace ply_slam
