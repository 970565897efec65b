#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace ply_slam {

// An object instance by its class and image box (pixels): what place recognition compares and
// a map file keeps of each keyframe.
struct InstanceBox {
  std::string class_name;
  cv::Rect2d box;
};

// The instances of one keyframe image.
struct InstanceFrame {
  cv::Size image_size;  // W x H, for the diagonal that normalises distances
  std::vector<InstanceBox> boxes;
};

}  // namespace ply_slam
