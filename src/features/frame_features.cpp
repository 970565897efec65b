#include "ply_slam/features/frame_features.h"

#include <algorithm>
#include <cmath>

#include "ply_slam/features/orb_extractor.h"

namespace ply_slam {

namespace {

float depthAt(const cv::Mat& depth_m, const PinholeCamera& camera, const cv::Point2f& raw) {
  const int u = cvRound(raw.x), v = cvRound(raw.y);
  if (u < 0 || v < 0 || u >= depth_m.cols || v >= depth_m.rows) return 0.f;
  const float d = depth_m.at<float>(v, u);
  return std::isfinite(d) && camera.validDepth(d) ? d : 0.f;
}

// Depth of the feature at rgb pixel `raw` in the rgb camera's frame. The depth image is
// registered to the raw rgb image but taken at another time; when the camera moved by
// T_depth_rgb in between, the feature's point is looked up where it was at depth time.
float lookupDepth(const cv::Mat& depth_m, const PinholeCamera& camera, const cv::Point2f& raw,
                  const Eigen::Vector2d& undistorted, const Eigen::Isometry3d* T_depth_rgb) {
  float z = depthAt(depth_m, camera, raw);
  if (!T_depth_rgb || z <= 0.f) return z;
  for (int iteration = 0; iteration < 2; ++iteration) {
    const Eigen::Vector3d p_depth = *T_depth_rgb * camera.backProject(undistorted, z);
    const Eigen::Vector2d moved = camera.project(p_depth);
    // The shift is a few pixels: undistortion changes it negligibly, so it is applied raw.
    const cv::Point2f shifted(static_cast<float>(raw.x + moved.x() - undistorted.x()),
                              static_cast<float>(raw.y + moved.y() - undistorted.y()));
    const float z_depth = depthAt(depth_m, camera, shifted);
    if (z_depth <= 0.f) return 0.f;
    const Eigen::Vector3d p_rgb = T_depth_rgb->inverse() * camera.backProject(moved, z_depth);
    z = static_cast<float>(p_rgb.z());
  }
  return camera.validDepth(z) ? z : 0.f;
}

// The grid cell of pixel coordinate x, -1 below the grid (or not a number) and `cells` beyond it:
// a far-off coordinate (a message's, a projection's) must not overflow the int.
int cellOf(double x, int cell_size, int cells) {
  const double cell = std::floor(x / cell_size);
  if (!(cell >= 0.0)) return -1;
  return cell >= cells ? cells : static_cast<int>(cell);
}

}  // namespace

FrameFeatures FrameFeatures::extract(const cv::Mat& gray, const cv::Mat& depth_m,
                                     const PinholeCamera& camera, const OrbExtractor& extractor,
                                     const CameraVelocity* velocity, double depth_dt) {
  FrameFeatures f;
  f.width = gray.cols;
  f.height = gray.rows;
  f.scales = &extractor.scales();
  extractor.extract(gray, f.keypoints, f.descriptors);

  const size_t n = f.keypoints.size();
  std::vector<cv::Point2f> raw(n);
  for (size_t i = 0; i < n; ++i) raw[i] = f.keypoints[i].pt;
  const std::vector<cv::Point2f> rectified = camera.undistortPixels(raw);
  f.rectified.resize(n);
  for (size_t i = 0; i < n; ++i) f.rectified[i] = Eigen::Vector2d(rectified[i].x, rectified[i].y);
  f.depth_image = depth_m;
  f.depth_dt = depth_dt;
  f.correctMotion(camera, velocity);
  return f;
}

void FrameFeatures::correctMotion(const PinholeCamera& camera, const CameraVelocity* velocity) {
  CV_Assert(!depth_image.empty());
  Eigen::Isometry3d T_depth_rgb;
  const Eigen::Isometry3d* T_depth_rgb_ptr = nullptr;
  if (velocity && depth_dt != 0.0) {
    T_depth_rgb = velocity->over(depth_dt);
    T_depth_rgb_ptr = &T_depth_rgb;
  }
  const size_t n = keypoints.size();
  undistorted = rectified;
  depth.assign(n, 0.f);
  for (size_t i = 0; i < n; ++i) {
    depth[i] = lookupDepth(depth_image, camera, keypoints[i].pt, rectified[i], T_depth_rgb_ptr);
    if (!velocity || camera.rolling_shutter_readout == 0.0) continue;
    // Row v was read tau after the middle row: move its observation to the stamp's pose.
    // The depth image has the same row timing, so the depth lookup above needs no change.
    const Eigen::Isometry3d T_stamp_row = velocity->over(-camera.rowTime(keypoints[i].pt.y));
    if (depth[i] > 0.f) {
      const Eigen::Vector3d p = T_stamp_row * camera.backProject(rectified[i], depth[i]);
      undistorted[i] = camera.project(p);
      depth[i] = camera.validDepth(p.z()) ? static_cast<float>(p.z()) : 0.f;
    } else {  // no depth: the rotation alone, which dominates at a distance
      undistorted[i] = camera.project(T_stamp_row.linear() * camera.backProject(rectified[i], 1.0));
    }
  }
  buildGrid();
}

size_t FrameFeatures::removeIf(const std::vector<bool>& drop) {
  CV_Assert(drop.size() == keypoints.size());
  size_t kept = 0;
  cv::Mat kept_descriptors;
  for (size_t i = 0; i < keypoints.size(); ++i) {
    if (drop[i]) continue;
    keypoints[kept] = keypoints[i];
    rectified[kept] = rectified[i];
    undistorted[kept] = undistorted[i];
    depth[kept] = depth[i];
    kept_descriptors.push_back(descriptors.row(static_cast<int>(i)));
    ++kept;
  }
  const size_t dropped = keypoints.size() - kept;
  keypoints.resize(kept);
  rectified.resize(kept);
  undistorted.resize(kept);
  depth.resize(kept);
  descriptors = kept_descriptors;
  buildGrid();
  return dropped;
}

void FrameFeatures::buildGrid() {
  grid_cols_ = std::max(1, (width + kCellSize - 1) / kCellSize);
  grid_rows_ = std::max(1, (height + kCellSize - 1) / kCellSize);
  grid_.assign(grid_cols_ * grid_rows_, {});
  for (size_t i = 0; i < undistorted.size(); ++i) {
    const int c = cellOf(undistorted[i].x(), kCellSize, grid_cols_);
    const int r = cellOf(undistorted[i].y(), kCellSize, grid_rows_);
    if (c < 0 || r < 0 || c >= grid_cols_ || r >= grid_rows_) continue;  // undistorted outside
    grid_[r * grid_cols_ + c].push_back(i);
  }
}

std::vector<size_t> FrameFeatures::featuresInArea(double u, double v, double radius, int min_level,
                                                  int max_level) const {
  std::vector<size_t> out;
  const int c0 = std::max(0, cellOf(u - radius, kCellSize, grid_cols_));
  const int c1 = std::min(grid_cols_ - 1, cellOf(u + radius, kCellSize, grid_cols_));
  const int r0 = std::max(0, cellOf(v - radius, kCellSize, grid_rows_));
  const int r1 = std::min(grid_rows_ - 1, cellOf(v + radius, kCellSize, grid_rows_));
  const double r2 = radius * radius;
  for (int r = r0; r <= r1; ++r) {
    for (int c = c0; c <= c1; ++c) {
      for (size_t i : grid_[r * grid_cols_ + c]) {
        const int level = keypoints[i].octave;
        if (level < min_level || level > max_level) continue;
        if ((undistorted[i] - Eigen::Vector2d(u, v)).squaredNorm() <= r2) out.push_back(i);
      }
    }
  }
  return out;
}

}  // namespace ply_slam
