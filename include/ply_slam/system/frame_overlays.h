#pragma once

#include <opencv2/core.hpp>
#include <vector>

#include "ply_slam/semantic/instance.h"
#include "ply_slam/system/system.h"

namespace ply_slam {

// Images for people watching a run (rviz, tracking_node's ~tracking_image and
// ~segmentation_image). Both take and return 8UC3 BGR.

// The frame's keypoints: used ones green, those dropped as dynamic red; state in a corner.
cv::Mat drawTrackingImage(const cv::Mat& bgr, const FrameResult& result);
// Instance masks blended over the image, moving classes red, others by class colour; labels.
cv::Mat drawSegmentationImage(const cv::Mat& bgr, const std::vector<Instance>& instances);

}  // namespace ply_slam
