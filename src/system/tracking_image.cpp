#include "ply_slam/system/tracking_image.h"

#include <cstdio>
#include <opencv2/imgproc.hpp>

namespace ply_slam {

cv::Mat drawTrackingImage(const cv::Mat& bgr, const FrameResult& result,
                          const std::vector<Instance>& instances) {
  cv::Mat image = bgr.clone();
  for (const auto& instance : instances) {
    std::vector<std::vector<cv::Point>> contours;
    cv::findContours(instance.mask, contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_SIMPLE);
    const bool dynamic = result.dynamic_instances.count(instance.id) > 0;
    const cv::Scalar colour = dynamic ? cv::Scalar(0, 0, 255) : cv::Scalar(0, 220, 255);
    cv::drawContours(image, contours, -1, colour, 2);
    if (!contours.empty()) {
      const cv::Rect box = cv::boundingRect(contours.front());
      cv::putText(image, instance.class_name + (dynamic ? " (dynamic)" : ""),
                  box.tl() + cv::Point(2, 14), cv::FONT_HERSHEY_SIMPLEX, 0.45, colour, 1,
                  cv::LINE_AA);
    }
  }
  int inliers = 0, kept = 0, geometric = 0, semantic = 0;
  for (const auto& f : result.features) {
    cv::Scalar colour;
    switch (f.fate) {
      case FeatureFate::kKept:
        colour = f.inlier ? cv::Scalar(0, 200, 0) : cv::Scalar(255, 120, 0);
        ++(f.inlier ? inliers : kept);
        break;
      case FeatureFate::kGeometric:
        colour = cv::Scalar(0, 0, 255);
        ++geometric;
        break;
      case FeatureFate::kSemantic:
        colour = cv::Scalar(255, 0, 255);
        ++semantic;
        break;
    }
    cv::circle(image, f.pixel, 3, colour, cv::FILLED, cv::LINE_AA);
  }
  char status[160];
  std::snprintf(status, sizeof(status),
                "frame %ld  %s  inliers %d  unused %d  dropped: Delaunay %d, instance %d",
                result.frame_id, toString(result.tracking.state), inliers, kept, geometric,
                semantic);
  cv::rectangle(image, cv::Rect(0, 0, image.cols, 20), cv::Scalar(0, 0, 0), cv::FILLED);
  cv::putText(image, status, {4, 14}, cv::FONT_HERSHEY_SIMPLEX, 0.45, cv::Scalar(255, 255, 255), 1,
              cv::LINE_AA);
  return image;
}

}  // namespace ply_slam
