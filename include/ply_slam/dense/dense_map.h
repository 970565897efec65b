#pragma once

#include <map>
#include <vector>

#include "ply_slam/dense/key_frame_cloud.h"
#include "ply_slam/map/key_frame_packet.h"

namespace ply_slam {

class SemanticOctree;

// The global dense cloud: keyframe clouds (kept in their camera frames) placed by their
// keyframes' current poses and voxel-filtered. Built when asked for, and again after a
// keyframe was added or its pose changed (memory: no world-frame copy per keyframe).
class DenseMap {
 public:
  explicit DenseMap(double voxel_size);

  // Adds a keyframe's cloud, or replaces the one of the same id.
  void insert(KeyFrameCloud cloud);
  // Drops the clouds of keyframes the sparse map erased (culled); unknown ids are ignored.
  // Returns how many were dropped.
  size_t erase(const std::vector<long>& ids);
  // Takes the corrected poses of known keyframes; returns the ids whose pose changed (by more
  // than 1e-6 m or rad), whose clouds will be re-placed. Unknown ids are ignored.
  std::vector<long> applyUpdate(const MapUpdate& update);

  // With an octree, the global cloud keeps only the points whose octree voxel is occupied:
  // what later rays found free (someone who walked away) or never confirmed is dropped.
  // The octree must outlive this map or be reset with nullptr.
  void keepOnlyOccupied(const SemanticOctree* octree);

  size_t numKeyFrames() const { return keyframes_.size(); }
  const std::map<long, KeyFrameCloud>& keyFrames() const { return keyframes_; }

  // The voxel-filtered world-frame cloud (rebuilt if anything changed since the last call).
  DenseCloudPtr globalCloud();
  size_t numGlobalPoints();      // of globalCloud(), for callers that do not include PCL
  size_t numUnfilteredPoints();  // of globalCloud() before keepOnlyOccupied's filter
  // Evaluation: how many points of the global cloud come mostly from tagged pixels (the
  // majority of the raw points merged into the point; ties do not count); -1 when some
  // keyframe has no tags. `unfiltered`: before keepOnlyOccupied's filter.
  long taggedPoints(bool unfiltered = false);
  // Bytes held by the keyframe clouds and the global cloud.
  size_t memoryBytes() const;

 private:
  void rebuild();

  double voxel_size_;
  std::map<long, KeyFrameCloud> keyframes_;
  const SemanticOctree* octree_ = nullptr;
  DenseCloudPtr global_, global_tags_;
  size_t unfiltered_points_ = 0;
  long unfiltered_tagged_ = -1;
  bool dirty_ = true;
};

}  // namespace ply_slam
