#include "ply_slam/dynamic/depth_surfaces.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <vector>

namespace ply_slam {
namespace {

bool valid(float z) { return std::isfinite(z) && z > 0.0f; }

// Two neighbours' depths are one surface: within the noise of either, and within the slope a
// surface seen at up to ~80 degrees from face-on has over `step` pixels (surfaceGap's 2 % of z
// at step 2: a floor three metres ahead changes by under 1 % from one step to the next).
bool sameSurface(float a, float b, const DepthNoiseModel& noise) {
  return valid(a) && valid(b) && std::abs(a - b) <= noise.surfaceGap(std::min(a, b));
}

}  // namespace

DepthSurfaces::DepthSurfaces(const cv::Mat& depth, const DepthNoiseModel& noise, int step,
                             int min_pixels)
    : step_(step), size_(depth.size()) {
  if (depth.type() != CV_32FC1 || depth.empty() || step < 1)
    throw std::invalid_argument("DepthSurfaces: needs a non-empty 32FC1 depth image, step >= 1");
  cv::Mat small;
  cv::resize(depth, small, cv::Size(depth.cols / step, depth.rows / step), 0, 0, cv::INTER_NEAREST);
  // A pixel beside a depth step belongs to neither side: connected components then stop there.
  // Each pair of neighbours is compared once: `joined_right` / `joined_down`.
  const int rows = small.rows, cols = small.cols;
  cv::Mat joined_right(rows, cols, CV_8UC1, cv::Scalar(1)),
      joined_down(rows, cols, CV_8UC1, cv::Scalar(1));
  for (int y = 0; y < rows; ++y) {
    const float* row = small.ptr<float>(y);
    const float* below = y + 1 < rows ? small.ptr<float>(y + 1) : nullptr;
    for (int x = 0; x < cols; ++x) {
      if (x + 1 < cols) joined_right.at<uchar>(y, x) = sameSurface(row[x], row[x + 1], noise);
      if (below) joined_down.at<uchar>(y, x) = sameSurface(row[x], below[x], noise);
    }
  }
  cv::Mat inside(small.size(), CV_8UC1);
  for (int y = 0; y < rows; ++y)
    for (int x = 0; x < cols; ++x)
      inside.at<uchar>(y, x) = valid(small.at<float>(y, x)) && joined_right.at<uchar>(y, x) &&
                               joined_down.at<uchar>(y, x) &&
                               (x == 0 || joined_right.at<uchar>(y, x - 1)) &&
                               (y == 0 || joined_down.at<uchar>(y - 1, x));
  cv::Mat stats, centroids;
  const int n = cv::connectedComponentsWithStats(inside, labels_, stats, centroids, 4, CV_32S);
  // Renumber the surfaces large enough to keep 1..count_.
  std::vector<int> renumbered(n, 0);
  const int min_area = std::max(1, min_pixels / (step * step));
  for (int label = 1; label < n; ++label)
    if (stats.at<int>(label, cv::CC_STAT_AREA) >= min_area) renumbered[label] = ++count_;
  for (int y = 0; y < labels_.rows; ++y) {
    int* row = labels_.ptr<int>(y);
    for (int x = 0; x < labels_.cols; ++x) row[x] = renumbered[row[x]];
  }
}

int DepthSurfaces::at(const cv::Point2f& pixel) const {
  const int x = cvFloor(pixel.x / step_), y = cvFloor(pixel.y / step_);
  if (x < 0 || y < 0 || x >= labels_.cols || y >= labels_.rows) return 0;
  return labels_.at<int>(y, x);
}

cv::Mat DepthSurfaces::paint(const std::map<int, uchar>& value, uchar none) const {
  std::vector<uchar> of(count_ + 1, none);
  for (const auto& [id, v] : value)
    if (id >= 1 && id <= count_) of[id] = v;
  cv::Mat small(labels_.size(), CV_8UC1);
  for (int y = 0; y < labels_.rows; ++y)
    for (int x = 0; x < labels_.cols; ++x) small.at<uchar>(y, x) = of[labels_.at<int>(y, x)];
  cv::Mat full;
  cv::resize(small, full, size_, 0, 0, cv::INTER_NEAREST);
  return full;
}

std::vector<DepthSurfaces::Overlap> DepthSurfaces::overlap(const cv::Mat& values,
                                                           uchar none) const {
  std::vector<std::vector<int>> histogram(count_, std::vector<int>(256, 0));
  std::vector<long> all(count_, 0);
  for (int y = 0; y < labels_.rows; ++y)
    for (int x = 0; x < labels_.cols; ++x) {
      const int id = labels_.at<int>(y, x);
      if (id == 0) continue;
      ++all[id - 1];
      const int mx = std::min(x * step_, values.cols - 1),
                my = std::min(y * step_, values.rows - 1);
      ++histogram[id - 1][values.at<uchar>(my, mx)];
    }
  std::vector<Overlap> result(count_);
  for (int i = 0; i < count_; ++i) {
    const long with_value = all[i] - histogram[i][none];
    if (with_value == 0) continue;
    result[i].share = static_cast<double>(with_value) / all[i];
    long seen = 0;
    for (int v = 0; v < 256; ++v) {
      if (v == none) continue;
      seen += histogram[i][v];
      if (2 * seen >= with_value) {
        result[i].median = v;
        break;
      }
    }
  }
  return result;
}

}  // namespace ply_slam
