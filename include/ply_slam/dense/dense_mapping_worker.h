#pragma once

#include <condition_variable>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "ply_slam/common/config.h"
#include "ply_slam/dense/dense_map.h"
#include "ply_slam/dense/key_frame_cloud_builder.h"
#include "ply_slam/dense/semantic_octree.h"

namespace ply_slam {

// Runs the dense map and the semantic octree in a thread of their own: the tracker hands
// packets over with push(), which only queues them, and never waits for the maps.
class DenseMappingWorker {
 public:
  explicit DenseMappingWorker(const DenseParams& params);
  ~DenseMappingWorker();  // finish()
  DenseMappingWorker(const DenseMappingWorker&) = delete;
  DenseMappingWorker& operator=(const DenseMappingWorker&) = delete;

  // Queues a keyframe. `tag_mask` (may be empty) marks pixels whose points are counted for
  // evaluation (see KeyFrameCloudBuilder). Throws std::logic_error after finish().
  void push(std::shared_ptr<const KeyFramePacket> packet, cv::Mat tag_mask = cv::Mat());
  // Queues pose corrections: changed keyframes are re-placed and the octree rebuilt.
  void push(const MapUpdate& update);
  // Queues the erasure of keyframes the sparse map culled: their clouds leave the dense map
  // (the keyframes that made them redundant see the same space). The octree keeps what they
  // added until it is rebuilt from the remaining clouds after a pose correction.
  void erase(std::vector<long> keyframe_ids);
  // Processes everything queued, then stops the thread. Idempotent.
  void finish();

  // Runs `f` with the maps while the worker is not changing them (e.g. to publish or save).
  void withMaps(const std::function<void(DenseMap&, const SemanticOctree&)>& f);

  // ms spent per keyframe (cloud + dense map + octree), in arrival order.
  std::vector<double> keyFrameMs() const;
  size_t maxQueueLength() const;
  // Packets that could not be used, and the first reason.
  size_t rejectedPackets() const;
  std::string firstError() const;

 private:
  DenseMappingWorker(const DenseParams& params, const ClassPalette& palette);  // palette read once

  struct Job {
    std::shared_ptr<const KeyFramePacket> packet;
    cv::Mat tag_mask;
    std::shared_ptr<const MapUpdate> update;
    std::vector<long> erased;  // keyframe ids
  };
  void run();
  void process(const Job& job);
  void enqueue(Job job);

  KeyFrameCloudBuilder builder_;
  DenseMap map_;
  SemanticOctree octree_;

  mutable std::mutex queue_mutex_;
  std::condition_variable queue_changed_;
  std::deque<Job> queue_;
  bool stopping_ = false;
  size_t max_queue_ = 0;
  std::vector<double> keyframe_ms_;
  size_t rejected_ = 0;
  std::string first_error_;

  std::mutex maps_mutex_;
  std::thread thread_;
};

}  // namespace ply_slam
