#pragma once

#include <Eigen/Geometry>
#include <opencv2/core.hpp>
#include <vector>

#include "ply_slam/common/camera_velocity.h"
#include "ply_slam/common/pinhole_camera.h"

namespace ply_slam {

class OrbExtractor;

// The point features of one RGB-D image: ORB keypoints, their undistorted pixel positions,
// their depth, and a grid for fixed-radius search.
struct FrameFeatures {
  std::vector<cv::KeyPoint> keypoints;          // raw image coordinates, octave = level
  std::vector<Eigen::Vector2d> rectified;       // undistorted, as imaged (rolling shutter and all)
  std::vector<Eigen::Vector2d> undistorted;     // at the stamp's pose: used by the geometry
  std::vector<float> depth;                     // m; 0 when invalid
  cv::Mat descriptors;                          // N x 32 CV_8U
  const std::vector<double>* scales = nullptr;  // scale per pyramid level (the extractor's)
  int width = 0, height = 0;
  cv::Mat depth_image;    // m; kept while the frame is tracked, released before it is stored
  double depth_dt = 0.0;  // s from the rgb to the depth exposure

  // Extracts features from a grey image and looks up depth at each raw keypoint. With the
  // camera's velocity known, motion during the exposure is undone: each keypoint is moved to
  // where it would appear at the frame's stamp (rolling shutter rows are read one after
  // another), and its depth is read where its point was when the depth image was taken,
  // depth_dt seconds after the rgb image.
  static FrameFeatures extract(const cv::Mat& gray, const cv::Mat& depth_m,
                               const PinholeCamera& camera, const OrbExtractor& extractor,
                               const CameraVelocity* velocity = nullptr, double depth_dt = 0.0);

  // Recomputes `undistorted` and `depth` from the raw measurements for a (better) velocity.
  void correctMotion(const PinholeCamera& camera, const CameraVelocity* velocity);

  // Drops feature i where drop[i] (one flag per feature). Returns how many were dropped.
  size_t removeIf(const std::vector<bool>& drop);

  size_t size() const { return keypoints.size(); }
  int level(size_t i) const { return keypoints[i].octave; }
  double scale(size_t i) const { return (*scales)[keypoints[i].octave]; }
  bool hasDepth(size_t i) const { return depth[i] > 0.f; }
  // Indices of features within `radius` px of (u, v) with level in [min_level, max_level].
  std::vector<size_t> featuresInArea(double u, double v, double radius, int min_level,
                                     int max_level) const;
  // The search grid over `undistorted` (extract and removeIf build it; a keyframe read from a
  // map file needs it built).
  void buildGrid();

 private:
  static constexpr int kCellSize = 16;
  int grid_cols_ = 0, grid_rows_ = 0;
  std::vector<std::vector<size_t>> grid_;
};

}  // namespace ply_slam
