#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "ply_slam/semantic/instance.h"

namespace ply_slam {

// An object instance as loop detection sees it: its class and its image box (pixels).
struct InstanceBox {
  std::string class_name;
  cv::Rect2d box;
};

// The instances of one keyframe image.
struct InstanceFrame {
  cv::Size image_size;  // W x H, for the diagonal that normalises distances
  std::vector<InstanceBox> boxes;
};

// Boxes of segmenter instances: the bounding rectangle of each mask's non-zero pixels.
// Instances with an empty mask have no box and are left out.
std::vector<InstanceBox> boxesFromInstances(const std::vector<Instance>& instances);

}  // namespace ply_slam
