#pragma once

#include <map>
#include <opencv2/core.hpp>
#include <vector>

#include "ply_slam/common/pinhole_camera.h"

namespace ply_slam {

// A depth image split into surfaces: neighbouring pixels belong to one surface unless their
// depths are further apart than one surface's noise and slope allow (DepthNoiseModel::
// surfaceGap). A person a metre in front of a room at three is a surface of its own, cut off by
// the depth step around it. Without a segmentation network these surfaces are the objects the
// dynamic check can judge as a whole: a body moving as a whole moves all of its features,
// including those the feature-wise check misses. Worked at 1/step of the resolution.
class DepthSurfaces {
 public:
  // depth: 32FC1 metres, 0 or NaN invalid; surfaces of fewer than min_pixels (full
  // resolution) are dropped (speckle, thin rims).
  DepthSurfaces(const cv::Mat& depth, const DepthNoiseModel& noise, int step = 2,
                int min_pixels = 400);

  // The surface under a raw image pixel: 1..count(), 0 for none.
  int at(const cv::Point2f& pixel) const;
  int count() const { return count_; }
  // 8UC1 at the depth image's size: value[id] on surface id, `none` elsewhere.
  cv::Mat paint(const std::map<int, uchar>& value, uchar none) const;
  // How a surface lies on an 8UC1 image of the depth image's size (`none`: no value there).
  struct Overlap {
    double share = 0.0;  // of its pixels that have a value
    int median = 0;      // of those values
  };
  std::vector<Overlap> overlap(const cv::Mat& values, uchar none) const;  // index id - 1

 private:
  cv::Mat labels_;  // CV_32S at 1/step_, 0 = none
  int step_;
  cv::Size size_;
  int count_ = 0;
};

}  // namespace ply_slam
