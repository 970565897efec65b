#include "ply_slam/features/depth_slope.h"

#include <cmath>

namespace ply_slam {
namespace {

float validDepth(const cv::Mat& depth_m, int u, int v) {
  if (u < 0 || v < 0 || u >= depth_m.cols || v >= depth_m.rows) return 0.f;
  const float d = depth_m.at<float>(v, u);
  return std::isfinite(d) && d > 0.f ? d : 0.f;
}

// The smaller one-sided difference from `centre` towards `before` and `after` (0 when missing).
double gentlerSide(float before, float centre, float after) {
  const bool has_before = before > 0.f, has_after = after > 0.f;
  if (!has_before && !has_after) return 0.0;
  const double back = centre - before, ahead = after - centre;
  if (!has_before) return ahead;
  if (!has_after) return back;
  return std::abs(back) < std::abs(ahead) ? back : ahead;
}

}  // namespace

Eigen::Vector2d depthSlopeAt(const cv::Mat& depth_m, int u, int v) {
  const float centre = validDepth(depth_m, u, v);
  if (centre <= 0.f) return Eigen::Vector2d::Zero();
  return {gentlerSide(validDepth(depth_m, u - 1, v), centre, validDepth(depth_m, u + 1, v)),
          gentlerSide(validDepth(depth_m, u, v - 1), centre, validDepth(depth_m, u, v + 1))};
}

Eigen::Vector2d depthSlopeOf(const FrameFeatures& features, size_t i) {
  if (features.depth_image.empty()) return Eigen::Vector2d::Zero();
  const cv::Point2f& raw = features.keypoints[i].pt;
  return depthSlopeAt(features.depth_image, cvRound(raw.x), cvRound(raw.y));
}

std::vector<Eigen::Vector2d> depthSlopes(const FrameFeatures& features) {
  std::vector<Eigen::Vector2d> slopes(features.size());
  for (size_t i = 0; i < features.size(); ++i) slopes[i] = depthSlopeOf(features, i);
  return slopes;
}

}  // namespace ply_slam
