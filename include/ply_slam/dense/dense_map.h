#pragma once

#include <map>
#include <vector>

#include "ply_slam/dense/key_frame_cloud.h"
#include "ply_slam/map/key_frame_packet.h"

namespace ply_slam {

// The global dense cloud: keyframe clouds (kept in their camera frames) placed by their
// keyframes' current poses and voxel-filtered. Built when asked for, and again after a
// keyframe was added or its pose changed (memory: no world-frame copy per keyframe).
class DenseMap {
 public:
  explicit DenseMap(double voxel_size);

  // Adds a keyframe's cloud, or replaces the one of the same id.
  void insert(KeyFrameCloud cloud);
  // Takes the corrected poses of known keyframes; returns the ids whose pose changed (by more
  // than 1e-6 m or rad), whose clouds will be re-placed. Unknown ids are ignored.
  std::vector<long> applyUpdate(const MapUpdate& update);

  size_t numKeyFrames() const { return keyframes_.size(); }
  const std::map<long, KeyFrameCloud>& keyFrames() const { return keyframes_; }

  // The voxel-filtered world-frame cloud (rebuilt if anything changed since the last call).
  DenseCloudPtr globalCloud();
  size_t numGlobalPoints();  // of globalCloud(), for callers that do not include PCL
  // Evaluation: how many points of the global cloud come mostly from tagged pixels (the
  // majority of the raw points merged into the point; ties do not count); -1 when some
  // keyframe has no tags.
  long taggedPoints();
  // Bytes held by the keyframe clouds and the global cloud.
  size_t memoryBytes() const;

 private:
  void rebuild();

  double voxel_size_;
  std::map<long, KeyFrameCloud> keyframes_;
  DenseCloudPtr global_, global_tags_;
  bool dirty_ = true;
};

}  // namespace ply_slam
