#pragma once

#include <opencv2/core.hpp>
#include <set>
#include <vector>

#include "ply_slam/semantic/instance.h"

namespace ply_slam {

// tracking_node's ~segmentation_image: instance masks blended over the 8UC3 BGR image, those
// judged moving (ids in `dynamic_ids`) red, the others in a colour per class, each labelled.
cv::Mat drawSegmentationImage(const cv::Mat& bgr, const std::vector<Instance>& instances,
                              const std::set<int>& dynamic_ids);

}  // namespace ply_slam
