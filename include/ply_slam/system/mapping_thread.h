#pragma once

#include <condition_variable>
#include <deque>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

#include "ply_slam/system/mapping_job.h"

namespace ply_slam {

// The mapping side on a thread of its own: jobs run one after the other in the order pushed;
// their results wait until the tracking side takes them.
class MappingThread {
 public:
  using Work = std::function<MappedKeyFrame(const MappingJob&)>;

  explicit MappingThread(Work work);
  // Runs the jobs still queued, then joins.
  ~MappingThread();
  MappingThread(const MappingThread&) = delete;
  MappingThread& operator=(const MappingThread&) = delete;

  void push(MappingJob job);
  // The results finished since the last call, in order. Throws std::runtime_error when a job
  // failed (what it threw); the thread goes on with the next.
  std::vector<MappedKeyFrame> takeFinished();
  // Blocks until every pushed job is done.
  void waitIdle();
  // The most jobs that were waiting at once.
  size_t longestQueue() const;
  // Jobs waiting or running now.
  size_t backlog() const;

 private:
  void run();

  Work work_;
  mutable std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<MappingJob> jobs_;
  std::vector<MappedKeyFrame> finished_;
  std::vector<std::string> failures_;
  size_t longest_queue_ = 0;
  bool busy_ = false;
  bool stopping_ = false;
  std::thread thread_;  // last: starts after everything it uses
};

}  // namespace ply_slam
