#pragma once

#include <memory>
#include <set>
#include <vector>

#include "ply_slam/map/map.h"

namespace ply_slam {

// When a keyframe says nothing its neighbours do not (ORB-SLAM's KeyFrameCulling).
struct KeyFrameCullerOptions {
  // ORB-SLAM: a keyframe goes when more than 90 % of its landmarks are redundant.
  double redundancy = 0.9;
  // ORB-SLAM (thObs): a landmark is redundant when this many other keyframes see it.
  int min_observers = 3;
  // ORB-SLAM: the other keyframe must see it at the same scale or finer, one level of slack
  // (its level <= this keyframe's level + 1): a coarser view does not replace a finer one.
  int level_slack = 1;
  // ORB-SLAM2 (MapPoint::EraseObservation: bad at <= 2 observations, an RGB-D view counting
  // two): a point left with one keyframe by the erasure is dropped.
  int min_point_observers = 2;
};

// Erases, among the covisible keyframes of a new keyframe, those whose landmarks are nearly
// all seen by enough other keyframes at the same or a finer scale. The map then grows with
// the places visited, not with the time spent in them.
class KeyFrameCuller {
 public:
  explicit KeyFrameCuller(const KeyFrameCullerOptions& options = {}) : options_(options) {}

  // Looks at `newest`'s covisible keyframes, most shared first; never erases `newest`, the
  // first keyframe or a keyframe in `keep` (e.g. the tracker's reference keyframe). Returns
  // the ids erased.
  std::vector<long> cull(Map& map, const KeyFrame& newest, const std::set<long>& keep) const;
  // The keyframe's landmarks are at least options.redundancy redundant (none: not redundant).
  bool redundant(const KeyFrame& keyframe) const;

 private:
  // Another `options.min_observers` keyframes see keypoint `index`'s landmark at its scale.
  bool seenByOthers(const KeyFrame& keyframe, size_t index) const;

  KeyFrameCullerOptions options_;
};

}  // namespace ply_slam
