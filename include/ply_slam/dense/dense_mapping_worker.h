#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "ply_slam/dense/dense_map.h"
#include "ply_slam/dense/dense_options.h"
#include "ply_slam/dense/key_frame_cloud_builder.h"
#include "ply_slam/dense/semantic_octree.h"

namespace ply_slam {

// Runs the dense map and the semantic octree in a thread of their own: the tracker hands
// packets over with push(), which only queues them, and never waits for the maps.
class DenseMappingWorker {
 public:
  explicit DenseMappingWorker(const DenseOptions& params);
  ~DenseMappingWorker();  // finish()
  DenseMappingWorker(const DenseMappingWorker&) = delete;
  DenseMappingWorker& operator=(const DenseMappingWorker&) = delete;

  // Queues a keyframe. `tag_mask` (may be empty) marks pixels whose points are counted for
  // evaluation (see KeyFrameCloudBuilder). Throws std::logic_error after finish().
  void push(std::shared_ptr<const KeyFramePacket> packet, cv::Mat tag_mask = cv::Mat());
  // Queues pose corrections: changed keyframes are re-placed and the octree rebuilt.
  void push(const MapUpdate& update);
  // Queues what the sparse map changed with a keyframe: the keyframes it culled leave the dense
  // map (those that made them redundant see the same space; the octree keeps what they added
  // until its next rebuild), and those still queued are dropped unbuilt (a worker that falls
  // behind catches up on the keyframes the map keeps instead of queueing every one made, images
  // and all); after a whole-map correction (a loop) the keyframes are re-placed as push(update)
  // does. Local BA's updates move nothing here: a rebuild for millimetres is not worth it.
  void follow(const MapUpdate& update);
  // Processes everything queued, then stops the thread. Idempotent.
  void finish();

  // Runs `f` with the maps while the worker is not changing them (e.g. to publish or save).
  // Within `f`, octreeRevision() names the octree `f` sees.
  void withMaps(const std::function<void(DenseMap&, const SemanticOctree&)>& f);

  std::uint64_t octreeRevision() const { return octree_revision_; }
  // ms spent per keyframe (cloud + dense map + octree), in arrival order.
  std::vector<double> keyFrameMs() const;
  size_t maxQueueLength() const;
  // Keyframes culled while still queued (follow): never built.
  size_t droppedUnbuilt() const;
  // Packets that could not be used, and the first reason.
  size_t rejectedPackets() const;
  std::string firstError() const;

 private:
  DenseMappingWorker(const DenseOptions& params, const ClassPalette& palette);  // palette read once

  struct Job {
    std::shared_ptr<const KeyFramePacket> packet;
    cv::Mat tag_mask;
    std::shared_ptr<const MapUpdate> update;
    std::vector<long> erased;  // keyframe ids
  };
  void run();
  void process(const Job& job);
  void enqueue(Job job);
  // Drops the queued packets of `erased`, then queues their erasure.
  void enqueueErasure(const std::vector<long>& erased);

  KeyFrameCloudBuilder builder_;
  DenseMap map_;
  SemanticOctree octree_;

  mutable std::mutex queue_mutex_;
  std::condition_variable queue_changed_;
  std::deque<Job> queue_;
  bool stopping_ = false;
  size_t max_queue_ = 0;
  size_t dropped_unbuilt_ = 0;
  std::vector<double> keyframe_ms_;
  size_t rejected_ = 0;
  std::string first_error_;

  std::mutex maps_mutex_;
  // Counts the octree's changes (written under maps_mutex_): what was derived from it can be
  // kept while it stays the same.
  std::atomic<std::uint64_t> octree_revision_{0};
  std::thread thread_;
};

}  // namespace ply_slam
