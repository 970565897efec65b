#include "ply_slam/system/mapping_thread.h"

#include <stdexcept>

namespace ply_slam {

MappingThread::MappingThread(Work work) : work_(std::move(work)), thread_([this] { run(); }) {}

MappingThread::~MappingThread() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  changed_.notify_all();
  thread_.join();
}

void MappingThread::push(MappingJob job) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    jobs_.push_back(std::move(job));
    longest_queue_ = std::max(longest_queue_, jobs_.size());
  }
  changed_.notify_all();
}

std::vector<MappedKeyFrame> MappingThread::takeFinished() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (!failures_.empty()) {
    const std::string failure = failures_.front();
    failures_.erase(failures_.begin());
    throw std::runtime_error("mapping side: " + failure);
  }
  std::vector<MappedKeyFrame> finished;
  finished.swap(finished_);
  return finished;
}

void MappingThread::waitIdle() {
  std::unique_lock<std::mutex> lock(mutex_);
  changed_.wait(lock, [this] { return jobs_.empty() && !busy_; });
}

size_t MappingThread::longestQueue() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return longest_queue_;
}

size_t MappingThread::backlog() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return jobs_.size() + (busy_ ? 1 : 0);
}

void MappingThread::run() {
  std::unique_lock<std::mutex> lock(mutex_);
  for (;;) {
    changed_.wait(lock, [this] { return stopping_ || !jobs_.empty(); });
    if (jobs_.empty()) return;  // stopping, and nothing left
    MappingJob job = std::move(jobs_.front());
    jobs_.pop_front();
    busy_ = true;
    lock.unlock();
    MappedKeyFrame result;
    std::string failure;
    try {
      result = work_(job);
    } catch (const std::exception& e) {
      failure = e.what();
    }
    lock.lock();
    busy_ = false;
    if (failure.empty())
      finished_.push_back(std::move(result));
    else
      failures_.push_back(failure);
    changed_.notify_all();
  }
}

}  // namespace ply_slam
