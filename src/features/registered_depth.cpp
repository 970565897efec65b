#include "ply_slam/features/registered_depth.h"

#include <algorithm>
#include <cmath>

namespace ply_slam {

RegisteredDepth::RegisteredDepth(const PinholeCamera& camera)
    : camera_(camera), inv_fx_(1.0 / camera.fx), inv_fy_(1.0 / camera.fy) {
  if (camera_.hasDistortion()) {
    cv::Mat k;
    camera_.distortion.convertTo(k, CV_64F);
    for (int i = 0; i < std::min<int>(5, static_cast<int>(k.total())); ++i) k_[i] = k.at<double>(i);
    distorted_ = true;
  }
}

Eigen::Vector2d RegisteredDepth::distort(const Eigen::Vector2d& undistorted) const {
  if (!distorted_) return undistorted;
  const double x = (undistorted.x() - camera_.cx) * inv_fx_;
  const double y = (undistorted.y() - camera_.cy) * inv_fy_;
  const double r2 = x * x + y * y;
  const double radial = 1.0 + r2 * (k_[0] + r2 * (k_[1] + r2 * k_[4]));
  const double xd = x * radial + 2.0 * k_[2] * x * y + k_[3] * (r2 + 2.0 * x * x);
  const double yd = y * radial + k_[2] * (r2 + 2.0 * y * y) + 2.0 * k_[3] * x * y;
  return {camera_.fx * xd + camera_.cx, camera_.fy * yd + camera_.cy};
}

}  // namespace ply_slam
