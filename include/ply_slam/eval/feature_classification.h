#pragma once

#include <opencv2/core.hpp>
#include <vector>

#include "ply_slam/dynamic/feature_mark.h"

namespace ply_slam {

// Counts, against ground-truth masks of the moving objects, what the dynamic rejection did
// with the features of each frame: features on a walker that still reached the
// pose optimisation, and static features that were dropped.
class FeatureClassification {
 public:
  // Features within this many px of a ground-truth mask count as neither walker nor static:
  // the masks' rims are uncertain by a pixel or two and the dilation is there on purpose.
  explicit FeatureClassification(int border_px = 5) : border_px_(border_px) {}

  // moving: 8UC1 union of the ground-truth masks of the moving objects (empty: none).
  void add(const std::vector<FeatureMark>& features, const cv::Mat& moving);

  long walkerFeatures() const { return walker_; }
  long walkerKept() const { return walker_kept_; }       // not dropped by the rejection
  long walkerInliers() const { return walker_inlier_; }  // used by the pose optimisation
  long staticFeatures() const { return static_; }
  long staticDropped() const { return static_dropped_; }
  double walkerKeptShare() const { return walker_ ? double(walker_kept_) / walker_ : 0.0; }
  double walkerInlierShare() const { return walker_ ? double(walker_inlier_) / walker_ : 0.0; }
  double staticDroppedShare() const { return static_ ? double(static_dropped_) / static_ : 0.0; }

 private:
  int border_px_;
  long walker_ = 0, walker_kept_ = 0, walker_inlier_ = 0, static_ = 0, static_dropped_ = 0;
};

}  // namespace ply_slam
