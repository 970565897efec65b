#pragma once

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <vector>

#include "ply_slam/features/frame_features.h"

namespace ply_slam {

// How steeply the depth image rises at a pixel, (dZ/du, dZ/dv) in m/px: per axis the smaller
// of the two one-sided differences, so that a depth edge beside the pixel (another surface) is
// not taken for the slope of the surface the pixel lies on; 0 along an axis with no valid
// neighbour. A feature's depth is read where its keypoint lies, so its pixel error moves its
// depth by this much per px (MeasuredPointNoise).
Eigen::Vector2d depthSlopeAt(const cv::Mat& depth_m, int u, int v);

// The slope under feature i's raw keypoint, where its depth was read; zero when the frame
// holds no depth image.
Eigen::Vector2d depthSlopeOf(const FrameFeatures& features, size_t i);
// depthSlopeOf every feature.
std::vector<Eigen::Vector2d> depthSlopes(const FrameFeatures& features);

}  // namespace ply_slam
