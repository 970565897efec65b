#include "ply_slam/semantic/segmentation_image.h"

#include <functional>
#include <opencv2/imgproc.hpp>
#include <string>

namespace ply_slam {
namespace {

// A stable colour per class name, bright enough to read over an image.
cv::Scalar classColour(const std::string& class_name) {
  const size_t h = std::hash<std::string>{}(class_name);
  return cv::Scalar(64 + h % 192, 64 + (h / 192) % 192, 64 + (h / 36864) % 192);
}

}  // namespace

cv::Mat drawSegmentationImage(const cv::Mat& bgr, const std::vector<Instance>& instances,
                              const std::set<int>& dynamic_ids) {
  cv::Mat out = bgr.clone();
  for (const auto& instance : instances) {
    if (instance.mask.size() != out.size() || instance.mask.type() != CV_8UC1) continue;
    const cv::Scalar colour =
        dynamic_ids.count(instance.id) ? cv::Scalar(0, 0, 255) : classColour(instance.class_name);
    cv::Mat blended;
    cv::addWeighted(out, 0.5, cv::Mat(out.size(), CV_8UC3, colour), 0.5, 0.0, blended);
    blended.copyTo(out, instance.mask);
    const cv::Rect box = cv::boundingRect(instance.mask);
    cv::putText(out, instance.class_name, box.tl() + cv::Point(2, 14), cv::FONT_HERSHEY_SIMPLEX,
                0.5, cv::Scalar(255, 255, 255), 1);
  }
  return out;
}

}  // namespace ply_slam
