#include "ply_slam/common/pinhole_camera.h"

#include <opencv2/calib3d.hpp>

namespace ply_slam {

bool PinholeCamera::hasDistortion() const {
  return !distortion.empty() && cv::countNonZero(distortion != 0.0) > 0;
}

std::vector<cv::Point2f> PinholeCamera::undistortPixels(const std::vector<cv::Point2f>& raw) const {
  if (raw.empty() || !hasDistortion()) return raw;
  std::vector<cv::Point2f> undistorted;
  cv::undistortPoints(raw, undistorted, K(), distortion, cv::noArray(), K());
  return undistorted;
}

}  // namespace ply_slam
