#pragma once

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "ply_slam/common/pinhole_camera.h"

namespace ply_slam {

// Reads of a depth image (CV_32F metres, 0 = invalid) registered to the raw rgb image, for
// points given in undistorted pixels: each read goes to the raw pixel the point was imaged at.
class RegisteredDepth {
 public:
  explicit RegisteredDepth(const PinholeCamera& camera);

  // Raw image pixel of an undistorted pixel (the camera's k1 k2 p1 p2 k3).
  Eigen::Vector2d distort(const Eigen::Vector2d& undistorted) const;
  // The raw displacement of an undistorted `step` taken at `undistorted`: distortion turns and
  // stretches little over a few pixels, so reads a few pixels apart step from one raw pixel.
  Eigen::Vector2d rawStep(const Eigen::Vector2d& undistorted, const Eigen::Vector2d& step) const {
    return distort(undistorted + step) - distort(undistorted);
  }
  // Depth (m) at the raw pixel nearest to `raw`; 0 when outside the image or invalid.
  // `rounding`, when given: the offset from `raw` to the centre of the pixel read.
  double atRaw(const cv::Mat& depth_m, const Eigen::Vector2d& raw,
               Eigen::Vector2d* rounding = nullptr) const {
    // The casts truncate, which is rounding once the position is > -0.5.
    if (!(raw.x() > -0.5 && raw.y() > -0.5)) return 0.0;
    const int u = static_cast<int>(raw.x() + 0.5), v = static_cast<int>(raw.y() + 0.5);
    if (u >= depth_m.cols || v >= depth_m.rows) return 0.0;
    const double z = depth_m.at<float>(v, u);
    if (!(z >= camera_.min_depth && z <= camera_.max_depth)) return 0.0;  // also NaN
    if (rounding) *rounding = Eigen::Vector2d(u - raw.x(), v - raw.y());
    return z;
  }

 private:
  PinholeCamera camera_;
  double inv_fx_, inv_fy_;
  double k_[5] = {0, 0, 0, 0, 0};  // k1 k2 p1 p2 k3
  bool distorted_ = false;
};

}  // namespace ply_slam
