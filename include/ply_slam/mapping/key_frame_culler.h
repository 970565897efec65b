#pragma once

#include <memory>
#include <set>
#include <vector>

#include "ply_slam/map/map.h"
#include "ply_slam/mapping/key_frame_culler_options.h"

namespace ply_slam {

// Erases, among the covisible keyframes of a new keyframe, those whose landmarks are nearly
// all seen by enough other keyframes at the same or a finer scale. The map then grows with
// the places visited, not with the time spent in them.
class KeyFrameCuller {
 public:
  explicit KeyFrameCuller(const KeyFrameCullerOptions& options = {}) : options_(options) {}

  // Looks at `newest`'s covisible keyframes, most shared first; never erases `newest`, one
  // made after it, the first keyframe or a keyframe in `keep` (e.g. the tracker's reference
  // keyframe). Returns the ids erased.
  std::vector<long> cull(Map& map, const KeyFrame& newest, const std::set<long>& keep) const;
  // The keyframe's landmarks are at least options.redundancy redundant (none: not redundant).
  bool redundant(const KeyFrame& keyframe) const;

 private:
  // Another `options.min_observers` keyframes see keypoint `index`'s landmark at its scale.
  bool seenByOthers(const KeyFrame& keyframe, size_t index) const;

  KeyFrameCullerOptions options_;
};

}  // namespace ply_slam
