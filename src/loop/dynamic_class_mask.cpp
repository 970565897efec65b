#include "ply_slam/loop/dynamic_class_mask.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

namespace ply_slam {

cv::Mat dynamicClassMask(const std::vector<Instance>& instances,
                         const std::vector<std::string>& classes, int dilation_px) {
  cv::Mat mask;
  for (const Instance& instance : instances) {
    if (instance.mask.empty() ||
        std::find(classes.begin(), classes.end(), instance.class_name) == classes.end())
      continue;
    if (mask.empty()) mask = cv::Mat::zeros(instance.mask.size(), CV_8UC1);
    mask.setTo(255, instance.mask);
  }
  if (!mask.empty() && dilation_px > 0)
    cv::dilate(mask, mask,
               cv::getStructuringElement(cv::MORPH_ELLIPSE,
                                         cv::Size(2 * dilation_px + 1, 2 * dilation_px + 1)));
  return mask;
}

bool onMask(const cv::Mat& mask, const Eigen::Vector2d& pixel) {
  if (mask.empty()) return false;
  const int u = static_cast<int>(std::lround(pixel.x())),
            v = static_cast<int>(std::lround(pixel.y()));
  return u >= 0 && v >= 0 && u < mask.cols && v < mask.rows && mask.at<uint8_t>(v, u) != 0;
}

cv::Mat keptRows(const cv::Mat& rows, const std::vector<bool>& keep) {
  cv::Mat out(0, rows.cols, rows.type());
  for (int r = 0; r < rows.rows; ++r)
    if (keep[r]) out.push_back(rows.row(r));
  return out;
}

}  // namespace ply_slam
