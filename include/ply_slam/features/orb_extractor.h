#pragma once

#include <opencv2/core.hpp>
#include <opencv2/features2d.hpp>
#include <vector>

#include "ply_slam/features/orb_options.h"

namespace ply_slam {

// ORB keypoints spread evenly over the image: per pyramid level, FAST corners are bucketed
// into grid cells (a lower FAST threshold is retried in empty cells) and taken round-robin,
// strongest first, so textured corners cannot crowd out the rest of the image. Keypoints
// come back in level-0 pixel coordinates with octave = pyramid level.
class OrbExtractor {
 public:
  explicit OrbExtractor(const OrbOptions& params);

  void extract(const cv::Mat& gray, std::vector<cv::KeyPoint>& keypoints,
               cv::Mat& descriptors) const;

  int numLevels() const { return params_.num_levels; }
  double scale(int level) const { return scales_[level]; }
  const std::vector<double>& scales() const { return scales_; }

 private:
  void detectLevel(const cv::Mat& image, int level, std::vector<cv::KeyPoint>& out) const;

  OrbOptions params_;
  std::vector<double> scales_;  // scale of level i relative to level 0
  std::vector<int> features_per_level_;
  std::vector<cv::Ptr<cv::ORB>> descriptors_;  // per level (thread safety): rBRIEF only
};

}  // namespace ply_slam
