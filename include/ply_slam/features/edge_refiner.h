#pragma once

#include <Eigen/Core>
#include <opencv2/core.hpp>

namespace ply_slam {

// Moves a detected segment onto the full-resolution edge it lies on. LSD run on a
// sub-sampled image (lines.lsd_scale) places edges to about half a pixel of the full image;
// the 3D fit reads depth at and beside the line, so at a surface seen at a grazing angle 4 m
// away that half pixel is 1-2 cm of depth. Along the segment the grey profile across it is
// sampled (bilinear, half-pixel steps), the strongest rise towards the brighter side (the
// segment's left) located to sub-pixel by a parabola, and a line fitted to those edge points
// (weighted by the rise, one round without points off by more than 0.75 px). A segment
// without enough edge points, or whose refined line moves or turns it by more than a small
// amount, is left as detected.
class EdgeRefiner {
 public:
  // Raw image pixels, brighter side on the left of start -> end. True when moved.
  static bool refine(const cv::Mat& gray, Eigen::Vector2d& start, Eigen::Vector2d& end);
};

}  // namespace ply_slam
