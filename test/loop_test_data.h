#pragma once

// Synthetic binary descriptors for the loop-module tests: random 256-bit centres and copies of
// them with a few bits flipped; their camera.
#include <opencv2/core.hpp>

#include <random>
#include <set>

#include "ply_slam/common/pinhole_camera.h"

namespace ply_slam::test {

// A 640 x 480 camera with a 500 px focal length.
inline PinholeCamera loopTestCamera() {
  PinholeCamera c;
  c.fx = c.fy = 500.0;
  c.cx = 320.0;
  c.cy = 240.0;
  c.width = 640;
  c.height = 480;
  return c;
}

inline cv::Mat randomDescriptors(int rows, std::mt19937& rng) {
  cv::Mat d(rows, 32, CV_8U);
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < 32; ++c) d.at<uint8_t>(r, c) = static_cast<uint8_t>(rng() & 0xFF);
  return d;
}

// The row with `flips` distinct random bits inverted.
inline cv::Mat flipBits(const cv::Mat& row, int flips, std::mt19937& rng) {
  cv::Mat out = row.clone();
  std::set<int> bits;
  while (static_cast<int>(bits.size()) < flips) bits.insert(static_cast<int>(rng() % 256));
  for (int bit : bits) out.at<uint8_t>(0, bit / 8) ^= static_cast<uint8_t>(1u << (bit % 8));
  return out;
}

// Every row of `descriptors` with `flips` bits inverted.
inline cv::Mat noisyCopy(const cv::Mat& descriptors, int flips, std::mt19937& rng) {
  cv::Mat out(descriptors.rows, descriptors.cols, CV_8U);
  for (int r = 0; r < descriptors.rows; ++r)
    flipBits(descriptors.row(r), flips, rng).copyTo(out.row(r));
  return out;
}

}  // namespace ply_slam::test
