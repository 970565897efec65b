#pragma once

#include <opencv2/core.hpp>
#include <string>

namespace ply_slam {

// One object instance in an image, from a segmenter.
struct Instance {
  int id = 0;              // unique within the image
  std::string class_name;  // COCO name, e.g. "person"
  float score = 1.0f;      // detection confidence (1 for ground-truth masks)
  cv::Mat mask;            // CV_8UC1 of the image size, non-zero on the instance
};

}  // namespace ply_slam
