#include "ply_slam/dense/dense_mapping_worker.h"

#include <algorithm>
#include <iterator>
#include <set>
#include <stdexcept>

#include "ply_slam/common/stopwatch.h"
#include "ply_slam/common/thread_priority.h"

namespace ply_slam {

DenseMappingWorker::DenseMappingWorker(const DenseOptions& params)
    : DenseMappingWorker(params, ClassPalette::configured(params.palette)) {}

DenseMappingWorker::DenseMappingWorker(const DenseOptions& params, const ClassPalette& palette)
    : builder_(params, palette),
      map_(params.voxel_size),
      octree_(params.octree_resolution, params.colour_mode, palette, params.octree_occupancy,
              params.ray_margin) {
  if (params.octree_filter) map_.keepOnlyOccupied(&octree_);
  thread_ = std::thread([this] {
    setThisThreadsNice(kBackgroundNice);  // maps to look at and plan on may lag; frames may not
    run();
  });
}

DenseMappingWorker::~DenseMappingWorker() { finish(); }

void DenseMappingWorker::enqueue(Job job) {
  {
    std::lock_guard<std::mutex> lock(queue_mutex_);
    if (stopping_) throw std::logic_error("DenseMappingWorker: push after finish()");
    queue_.push_back(std::move(job));
    max_queue_ = std::max(max_queue_, queue_.size());
  }
  queue_changed_.notify_one();
}

void DenseMappingWorker::push(std::shared_ptr<const KeyFramePacket> packet, cv::Mat tag_mask) {
  if (!packet) throw std::invalid_argument("DenseMappingWorker::push: null packet");
  enqueue({std::move(packet), std::move(tag_mask), nullptr, {}});
}

void DenseMappingWorker::follow(const MapUpdate& update) {
  if (!update.erased_keyframes.empty()) enqueueErasure(update.erased_keyframes);
  if (update.whole_map) push(update);
}

void DenseMappingWorker::enqueueErasure(const std::vector<long>& erased) {
  {
    std::lock_guard<std::mutex> lock(queue_mutex_);
    const std::set<long> ids(erased.begin(), erased.end());
    const auto unbuilt = std::remove_if(queue_.begin(), queue_.end(), [&ids](const Job& job) {
      return job.packet && ids.count(job.packet->id) > 0;
    });
    dropped_unbuilt_ += static_cast<size_t>(std::distance(unbuilt, queue_.end()));
    queue_.erase(unbuilt, queue_.end());
  }
  enqueue({nullptr, cv::Mat(), nullptr, erased});
}

void DenseMappingWorker::push(const MapUpdate& update) {
  enqueue({nullptr, cv::Mat(), std::make_shared<const MapUpdate>(update), {}});
}

void DenseMappingWorker::finish() {
  {
    std::lock_guard<std::mutex> lock(queue_mutex_);
    stopping_ = true;
  }
  queue_changed_.notify_one();
  if (thread_.joinable()) thread_.join();
}

void DenseMappingWorker::run() {
  for (;;) {
    Job job;
    {
      std::unique_lock<std::mutex> lock(queue_mutex_);
      queue_changed_.wait(lock, [this] { return stopping_ || !queue_.empty(); });
      if (queue_.empty()) return;  // stopping, and everything is done
      job = std::move(queue_.front());
      queue_.pop_front();
    }
    process(job);
  }
}

void DenseMappingWorker::process(const Job& job) {
  try {
    if (job.packet) {
      Stopwatch watch;
      // The cloud is built outside the maps' lock: readers wait only for the insertion.
      KeyFrameCloud cloud = builder_.build(*job.packet, job.tag_mask);
      {
        std::lock_guard<std::mutex> lock(maps_mutex_);
        octree_.insert(cloud);
        map_.insert(std::move(cloud));
        ++octree_revision_;
      }
      const double ms = watch.elapsedMs();
      std::lock_guard<std::mutex> lock(queue_mutex_);
      keyframe_ms_.push_back(ms);
    } else if (job.update) {
      std::lock_guard<std::mutex> lock(maps_mutex_);
      if (map_.applyUpdate(*job.update).empty()) return;
      // Ray casting cannot be undone per keyframe: the octree is rebuilt in keyframe order.
      octree_.clear();
      for (const auto& [id, cloud] : map_.keyFrames()) octree_.insert(cloud);
      ++octree_revision_;
    } else if (!job.erased.empty()) {
      std::lock_guard<std::mutex> lock(maps_mutex_);
      map_.erase(job.erased);
    }
  } catch (const std::exception& e) {
    std::lock_guard<std::mutex> lock(queue_mutex_);
    if (rejected_++ == 0) first_error_ = e.what();
  }
}

void DenseMappingWorker::withMaps(const std::function<void(DenseMap&, const SemanticOctree&)>& f) {
  std::lock_guard<std::mutex> lock(maps_mutex_);
  f(map_, octree_);
}

std::vector<double> DenseMappingWorker::keyFrameMs() const {
  std::lock_guard<std::mutex> lock(queue_mutex_);
  return keyframe_ms_;
}

size_t DenseMappingWorker::maxQueueLength() const {
  std::lock_guard<std::mutex> lock(queue_mutex_);
  return max_queue_;
}

size_t DenseMappingWorker::droppedUnbuilt() const {
  std::lock_guard<std::mutex> lock(queue_mutex_);
  return dropped_unbuilt_;
}

size_t DenseMappingWorker::rejectedPackets() const {
  std::lock_guard<std::mutex> lock(queue_mutex_);
  return rejected_;
}

std::string DenseMappingWorker::firstError() const {
  std::lock_guard<std::mutex> lock(queue_mutex_);
  return first_error_;
}

}  // namespace ply_slam
