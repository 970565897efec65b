#pragma once

#include <opencv2/core.hpp>
#include <set>
#include <vector>

#include "ply_slam/semantic/instance.h"
#include "ply_slam/system/system.h"

namespace ply_slam {

// The tracking image (ply_slam_tum --save-images, tracking_node's ~tracking_image): the frame with
// its instances outlined (red: judged dynamic, yellow: kept), features as dots — green: an inlier
// of the pose optimisation, blue: kept but not used, red: dropped by the Delaunay check,
// magenta: dropped with a dynamic instance — and a status line.
cv::Mat drawTrackingImage(const cv::Mat& bgr, const FrameResult& result,
                          const std::vector<Instance>& instances);

}  // namespace ply_slam
