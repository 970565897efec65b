#pragma once

#include <opencv2/core.hpp>

namespace ply_slam {

// One RGB-D frame as the library takes it, whatever its source (a TUM folder, ROS messages):
// rgb is 8UC3 BGR, depth is CV_32F in metres (0 = invalid).
struct RgbdImages {
  double stamp = 0.0;        // rgb stamp
  double depth_stamp = 0.0;  // when the depth image was taken; 0 = with the rgb image
  cv::Mat rgb;
  cv::Mat depth;
};

}  // namespace ply_slam
