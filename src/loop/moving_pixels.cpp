#include "ply_slam/loop/moving_pixels.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

namespace ply_slam {

cv::Mat movingPixels(const cv::Mat& label_image, const std::vector<PacketInstance>& instances,
                     const std::vector<std::string>& moving_classes, int dilation_px) {
  cv::Mat movers;
  if (label_image.empty()) return movers;
  for (const PacketInstance& instance : instances) {
    if (std::find(moving_classes.begin(), moving_classes.end(), instance.class_name) ==
        moving_classes.end())
      continue;
    if (movers.empty()) movers = cv::Mat::zeros(label_image.size(), CV_8UC1);
    movers.setTo(255, label_image == instance.id);
  }
  if (!movers.empty() && dilation_px > 0) {
    const int size = 2 * dilation_px + 1;
    cv::dilate(movers, movers, cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(size, size)));
  }
  return movers;
}

std::vector<bool> offMask(const std::vector<Eigen::Vector2d>& points, const cv::Mat& mask) {
  std::vector<bool> off(points.size(), true);
  if (mask.empty()) return off;
  for (size_t i = 0; i < points.size(); ++i) {
    const int u = static_cast<int>(std::lround(points[i].x())),
              v = static_cast<int>(std::lround(points[i].y()));
    off[i] = !(u >= 0 && v >= 0 && u < mask.cols && v < mask.rows && mask.at<uint8_t>(v, u) != 0);
  }
  return off;
}

cv::Mat keptRows(const cv::Mat& rows, const std::vector<bool>& keep) {
  cv::Mat out(0, rows.cols, rows.type());
  for (int r = 0; r < rows.rows; ++r)
    if (keep[r]) out.push_back(rows.row(r));
  return out;
}

}  // namespace ply_slam
