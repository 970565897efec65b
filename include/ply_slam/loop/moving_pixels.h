#pragma once

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "ply_slam/map/key_frame_packet.h"

namespace ply_slam {

// Place recognition leaves out what lies on instances of moving classes (LoopOptions::
// dynamic_classes): a person's features match the same person anywhere. The pixels of those
// instances in `label_image` (16UC1 instance ids, may be empty), dilated by `dilation_px`:
// 8UC1, non-zero on them; empty when there are none.
cv::Mat movingPixels(const cv::Mat& label_image, const std::vector<PacketInstance>& instances,
                     const std::vector<std::string>& moving_classes, int dilation_px);

// Per point, whether it (rounded) lies off `mask` (every one for an empty mask).
std::vector<bool> offMask(const std::vector<Eigen::Vector2d>& points, const cv::Mat& mask);
// The rows of `rows` whose `keep` is true, in order.
cv::Mat keptRows(const cv::Mat& rows, const std::vector<bool>& keep);

}  // namespace ply_slam
