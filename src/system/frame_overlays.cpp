#include "ply_slam/system/frame_overlays.h"

#include <functional>
#include <opencv2/imgproc.hpp>
#include <string>

#include "ply_slam/semantic/dynamic_classes.h"

namespace ply_slam {
namespace {

const cv::Scalar kStatic(0, 220, 0);
const cv::Scalar kDynamic(0, 0, 255);

// A stable colour per class name, bright enough to read over an image.
cv::Scalar classColour(const std::string& class_name) {
  const size_t h = std::hash<std::string>{}(class_name);
  return cv::Scalar(64 + h % 192, 64 + (h / 192) % 192, 64 + (h / 36864) % 192);
}

}  // namespace

cv::Mat drawTrackingImage(const cv::Mat& bgr, const FrameResult& result) {
  cv::Mat out = bgr.clone();
  for (const auto& kp : result.keypoints) cv::circle(out, kp.pt, 3, kStatic, 1, cv::LINE_AA);
  for (const auto& kp : result.dynamic_keypoints) {
    const cv::Point2f d(3, 3);
    cv::line(out, kp.pt - d, kp.pt + d, kDynamic, 1, cv::LINE_AA);
    cv::line(out, kp.pt + cv::Point2f(-3, 3), kp.pt + cv::Point2f(3, -3), kDynamic, 1, cv::LINE_AA);
  }
  const std::string text = std::string(toString(result.tracking.state)) + "  " +
                           result.tracking.method + "  inliers " +
                           std::to_string(result.tracking.inliers) + "  dynamic " +
                           std::to_string(result.dynamic_features);
  cv::putText(out, text, {8, 20}, cv::FONT_HERSHEY_SIMPLEX, 0.55, cv::Scalar(0, 0, 0), 3);
  cv::putText(out, text, {8, 20}, cv::FONT_HERSHEY_SIMPLEX, 0.55, cv::Scalar(255, 255, 255), 1);
  return out;
}

cv::Mat drawSegmentationImage(const cv::Mat& bgr, const std::vector<Instance>& instances) {
  cv::Mat out = bgr.clone();
  for (const auto& instance : instances) {
    if (instance.mask.size() != out.size()) continue;
    const cv::Scalar colour =
        isActiveDynamicClass(instance.class_name) ? kDynamic : classColour(instance.class_name);
    cv::Mat tint(out.size(), CV_8UC3, colour);
    cv::Mat blended;
    cv::addWeighted(out, 0.5, tint, 0.5, 0.0, blended);
    blended.copyTo(out, instance.mask);
    const cv::Rect box = cv::boundingRect(instance.mask);
    cv::putText(out, instance.class_name, box.tl() + cv::Point(2, 14), cv::FONT_HERSHEY_SIMPLEX,
                0.5, cv::Scalar(255, 255, 255), 1);
  }
  return out;
}

}  // namespace ply_slam
