#pragma once

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "ply_slam/semantic/instance.h"

namespace ply_slam {

// The pixels of the instances of potentially moving classes (LoopOptions::dynamic_classes),
// dilated by dilation_px (masks miss the blurred rim). A place is recognised by what stays:
// a person's features match the same person anywhere, and a walker seen twice is a rigid
// pattern that even the geometric check accepts, with the person's motion as the "loop".
// Empty when no instance is of those classes.
cv::Mat dynamicClassMask(const std::vector<Instance>& instances,
                         const std::vector<std::string>& classes, int dilation_px);

// Whether the pixel (rounded) lies on the mask; false for an empty mask or outside it.
bool onMask(const cv::Mat& mask, const Eigen::Vector2d& pixel);

// The rows of `rows` whose keep flag is set, in order.
cv::Mat keptRows(const cv::Mat& rows, const std::vector<bool>& keep);

}  // namespace ply_slam
