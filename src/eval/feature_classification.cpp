#include "ply_slam/eval/feature_classification.h"

#include <algorithm>
#include <opencv2/imgproc.hpp>

namespace ply_slam {

void FeatureClassification::add(const std::vector<FeatureMark>& features, const cv::Mat& moving) {
  cv::Mat near;
  if (!moving.empty() && border_px_ > 0)
    cv::dilate(moving, near,
               cv::getStructuringElement(cv::MORPH_ELLIPSE,
                                         cv::Size(2 * border_px_ + 1, 2 * border_px_ + 1)));
  else
    near = moving;
  for (const auto& f : features) {
    bool on = false, close = false;
    if (!moving.empty()) {
      const int x = std::clamp(cvRound(f.pixel.x), 0, moving.cols - 1);
      const int y = std::clamp(cvRound(f.pixel.y), 0, moving.rows - 1);
      on = moving.at<uchar>(y, x) != 0;
      close = near.at<uchar>(y, x) != 0;
    }
    const bool dropped = f.fate != FeatureFate::kKept;
    if (on) {
      ++walker_;
      walker_kept_ += !dropped;
      walker_inlier_ += f.inlier;
    } else if (!close) {
      ++static_;
      static_dropped_ += dropped;
    }
  }
}

}  // namespace ply_slam
