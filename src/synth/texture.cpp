#include "ply_slam/synth/texture.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

namespace ply_slam {
namespace {

inline int wrapIndex(int i, int n, bool repeat) {
  if (repeat) {
    i %= n;
    return i < 0 ? i + n : i;
  }
  return std::clamp(i, 0, n - 1);
}

}  // namespace

Texture::Texture(const cv::Mat& image, std::string name) : name_(std::move(name)) {
  if (image.empty()) throw std::invalid_argument("texture " + name_ + ": empty image");
  cv::Mat level;
  if (image.type() == CV_8UC1) {
    cv::cvtColor(image, level, cv::COLOR_GRAY2BGR);
  } else if (image.type() == CV_8UC3) {
    level = image.clone();
  } else {
    throw std::invalid_argument("texture " + name_ + ": needs an 8-bit grey or BGR image");
  }
  levels_.push_back(level);
  scale_.emplace_back(1.0f, 1.0f);
  // Halve until the image is tiny; INTER_AREA is a box filter, the classic mip-map kernel.
  while (level.cols > 4 && level.rows > 4) {
    cv::Mat next;
    cv::resize(level, next, cv::Size((level.cols + 1) / 2, (level.rows + 1) / 2), 0, 0,
               cv::INTER_AREA);
    levels_.push_back(next);
    scale_.emplace_back(static_cast<float>(next.cols) / levels_[0].cols,
                        static_cast<float>(next.rows) / levels_[0].rows);
    level = next;
  }
}

cv::Vec3f Texture::bilinear(int level, float s, float t, bool repeat) const {
  const cv::Mat& img = levels_[level];
  // Texel centres sit at i + 0.5.
  const float x = s * scale_[level][0] - 0.5f;
  const float y = t * scale_[level][1] - 0.5f;
  const float fx = std::floor(x), fy = std::floor(y);
  const float wx = x - fx, wy = y - fy;
  const int x0 = wrapIndex(static_cast<int>(fx), img.cols, repeat);
  const int x1 = wrapIndex(static_cast<int>(fx) + 1, img.cols, repeat);
  const int y0 = wrapIndex(static_cast<int>(fy), img.rows, repeat);
  const int y1 = wrapIndex(static_cast<int>(fy) + 1, img.rows, repeat);
  const cv::Vec3b* r0 = img.ptr<cv::Vec3b>(y0);
  const cv::Vec3b* r1 = img.ptr<cv::Vec3b>(y1);
  cv::Vec3f out;
  for (int c = 0; c < 3; ++c) {
    const float top = r0[x0][c] + wx * (r0[x1][c] - r0[x0][c]);
    const float bottom = r1[x0][c] + wx * (r1[x1][c] - r1[x0][c]);
    out[c] = (top + wy * (bottom - top)) * (1.0f / 255.0f);
  }
  return out;
}

cv::Vec3f Texture::sample(float s, float t, float lod, bool repeat) const {
  const int last = levels() - 1;
  if (!(lod > 0.0f)) return bilinear(0, s, t, repeat);  // magnified (or NaN): finest level
  if (lod >= last) return bilinear(last, s, t, repeat);
  const int level = static_cast<int>(lod);
  const float w = lod - level;
  return bilinear(level, s, t, repeat) * (1.0f - w) + bilinear(level + 1, s, t, repeat) * w;
}

}  // namespace ply_slam
