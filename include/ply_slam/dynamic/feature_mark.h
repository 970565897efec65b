#pragma once

#include <opencv2/core.hpp>

namespace ply_slam {

// Why a feature was left out of tracking, or that it was kept.
enum class FeatureFate : unsigned char { kKept, kGeometric, kSemantic };

// One extracted point feature and what became of it (for the tracking image and reports).
struct FeatureMark {
  cv::Point2f pixel;  // raw image
  FeatureFate fate = FeatureFate::kKept;
  bool inlier = false;  // kept, matched to a landmark and an inlier of the pose optimisation
};

}  // namespace ply_slam
