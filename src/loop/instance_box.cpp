#include "ply_slam/loop/instance_box.h"

#include <opencv2/imgproc.hpp>

namespace ply_slam {

std::vector<InstanceBox> boxesFromInstances(const std::vector<Instance>& instances) {
  std::vector<InstanceBox> boxes;
  for (const Instance& instance : instances) {
    if (instance.mask.empty()) continue;
    // On an 8-bit single-channel image boundingRect bounds its non-zero pixels.
    const cv::Rect rect = cv::boundingRect(instance.mask);
    if (rect.area() == 0) continue;
    boxes.push_back({instance.class_name, cv::Rect2d(rect)});
  }
  return boxes;
}

}  // namespace ply_slam
