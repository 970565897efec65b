#pragma once

#include <Eigen/Geometry>
#include <opencv2/core.hpp>
#include <vector>

#include "ply_slam/common/pinhole_camera.h"

namespace ply_slam {

class OrbExtractor;

// The point features of one RGB-D image: ORB keypoints, their undistorted pixel positions,
// their depth, and a grid for fixed-radius search.
struct FrameFeatures {
  std::vector<cv::KeyPoint> keypoints;          // raw image coordinates, octave = level
  std::vector<Eigen::Vector2d> undistorted;     // pixel coordinates used by the geometry
  std::vector<float> depth;                     // m; 0 when invalid
  cv::Mat descriptors;                          // N x 32 CV_8U
  const std::vector<double>* scales = nullptr;  // scale per pyramid level (the extractor's)
  int width = 0, height = 0;

  // Extracts features from a grey image and looks up depth at each raw keypoint.
  // T_depth_rgb, when given, is the camera motion from the rgb to the depth exposure: the
  // depth of each feature is then read where its point was at depth time.
  static FrameFeatures extract(const cv::Mat& gray, const cv::Mat& depth_m,
                               const PinholeCamera& camera, const OrbExtractor& extractor,
                               const Eigen::Isometry3d* T_depth_rgb = nullptr);

  size_t size() const { return keypoints.size(); }
  int level(size_t i) const { return keypoints[i].octave; }
  double scale(size_t i) const { return (*scales)[keypoints[i].octave]; }
  bool hasDepth(size_t i) const { return depth[i] > 0.f; }
  // Indices of features within `radius` px of (u, v) with level in [min_level, max_level].
  std::vector<size_t> featuresInArea(double u, double v, double radius, int min_level,
                                     int max_level) const;

 private:
  static constexpr int kCellSize = 16;
  void buildGrid();
  int grid_cols_ = 0, grid_rows_ = 0;
  std::vector<std::vector<size_t>> grid_;
};

}  // namespace ply_slam
