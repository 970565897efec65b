#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <opencv2/core.hpp>
#include <vector>

namespace ply_slam {

// Depth-sensor noise, variance in m^2: sigma_Z^2 = alpha Z^2 + beta Z + gamma (PAPER.md §3.1)
// within one frame and between frames a moment apart. A depth compared with a landmark mapped
// from other views has a second error: depth from disparity (structured light, stereo) comes
// with a spatially varying disparity distortion sigma_d that does not average out as the point
// crosses the image, sigma_Z = Z^2 sigma_d / (b f): delta Z^4 with delta = (sigma_d / (b f))^2.
// Defaults: alpha, beta, gamma as in config/tum_fr1.yaml (sigma_Z = 5 mm at 1 m), delta 0.
struct DepthNoiseModel {
  double alpha = 2.5e-5;
  double beta = 0.0;
  double gamma = 1.0e-5;
  double delta = 0.0;
  double variance(double z) const { return alpha * z * z + beta * z + gamma; }
  // A measured depth against a landmark's depth mapped from other views.
  double varianceAgainstMap(double z) const { return variance(z) + delta * z * z * z * z; }
  // Two depths near z further apart than this are two surfaces (a step at an occluding
  // edge), not one surface's noise: 3 sigma, and at least 2 % of z for unmodelled errors.
  double surfaceGap(double z) const { return std::max(3.0 * std::sqrt(variance(z)), 0.02 * z); }
};

// Pinhole RGB-D camera. Pixel coordinates used by the algorithms are undistorted;
// `distortion` (OpenCV k1 k2 p1 p2 k3) maps raw image pixels to them.
struct PinholeCamera {
  double fx = 0.0, fy = 0.0, cx = 0.0, cy = 0.0;
  int width = 0, height = 0;
  cv::Mat distortion;            // 1x5 CV_64F, empty or all zero when the image is rectified
  double depth_factor = 5000.0;  // raw 16-bit depth units per metre
  double min_depth = 0.1;        // m; depth outside [min_depth, max_depth] counts as invalid
  double max_depth = 8.0;
  DepthNoiseModel depth_noise;
  double rolling_shutter_readout = 0.0;  // s from first to last row; 0 = global shutter

  // The pixel uv of the camera-frame point p_c: the one pinhole projection (also for Ceres'
  // Jets). The caller keeps p_c in front of the camera.
  template <typename T>
  void project(const T* p_c, T* uv) const {
    uv[0] = T(fx) * p_c[0] / p_c[2] + T(cx);
    uv[1] = T(fy) * p_c[1] / p_c[2] + T(cy);
  }
  Eigen::Vector2d project(const Eigen::Vector3d& p_c) const {
    Eigen::Vector2d uv;
    project(p_c.data(), uv.data());
    return uv;
  }
  Eigen::Vector3d backProject(const Eigen::Vector2d& uv, double depth) const {
    return {(uv.x() - cx) * depth / fx, (uv.y() - cy) * depth / fy, depth};
  }
  bool inImage(const Eigen::Vector2d& uv, double border = 0.0) const {
    return uv.x() >= border && uv.y() >= border && uv.x() < width - border &&
           uv.y() < height - border;
  }
  bool validDepth(double z) const { return z >= min_depth && z <= max_depth; }
  // When raw image row v was read, relative to the middle row (the stamp): rolling shutter.
  double rowTime(double v) const { return (v / height - 0.5) * rolling_shutter_readout; }
  bool hasDistortion() const;
  // Undistorted pixels of raw image pixels (the same pixels when there is no distortion).
  std::vector<cv::Point2f> undistortPixels(const std::vector<cv::Point2f>& raw) const;
  cv::Matx33d K() const { return {fx, 0, cx, 0, fy, cy, 0, 0, 1}; }
};

}  // namespace ply_slam
