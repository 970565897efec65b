#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace ply_slam {

// A photograph used as surface texture, with a mip-map pyramid so that distant or slanted
// surfaces are filtered instead of aliased (aliasing would make ORB corners flicker between
// frames, which no real camera does).
class Texture {
 public:
  Texture() = default;
  // image: 8UC3 BGR (8UC1 is converted). Levels are built down to a few texels.
  Texture(const cv::Mat& image, std::string name);

  const std::string& name() const { return name_; }
  int width() const { return levels_.empty() ? 0 : levels_[0].cols; }
  int height() const { return levels_.empty() ? 0 : levels_[0].rows; }
  int levels() const { return static_cast<int>(levels_.size()); }

  // Colour in [0, 1] (BGR) at texel coordinates (s, t) of level 0, where texel (i, j) covers
  // [i, i + 1) x [j, j + 1). lod = log2(texels per pixel): trilinear between mip levels.
  // repeat: tile the image, else clamp to its border.
  cv::Vec3f sample(float s, float t, float lod, bool repeat) const;

 private:
  cv::Vec3f bilinear(int level, float s, float t, bool repeat) const;

  std::string name_;
  std::vector<cv::Mat> levels_;   // 8UC3
  std::vector<cv::Vec2f> scale_;  // level texels per level-0 texel (x, y)
};

}  // namespace ply_slam
