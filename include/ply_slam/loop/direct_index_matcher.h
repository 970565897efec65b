#pragma once

#include <opencv2/core.hpp>
#include <utility>
#include <vector>

#include "ply_slam/loop/bow_vector.h"

namespace ply_slam {

// Feature matches between two keyframes through their direct indexes: only descriptors under
// the same vocabulary node are compared (Gálvez-López & Tardós 2012, §4), a feature's best
// match is kept when within max_distance and below ratio x the second best, and each feature
// of b keeps only its closest a.
class DirectIndexMatcher {
 public:
  DirectIndexMatcher(int max_distance, double ratio);

  // (index in a, index in b) pairs, sorted by index in a.
  std::vector<std::pair<int, int>> match(const FeatureVector& features_a,
                                         const cv::Mat& descriptors_a,
                                         const FeatureVector& features_b,
                                         const cv::Mat& descriptors_b) const;

 private:
  int max_distance_;
  double ratio_;
};

}  // namespace ply_slam
