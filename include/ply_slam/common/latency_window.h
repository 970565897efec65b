#pragma once

#include <algorithm>
#include <cstddef>
#include <deque>
#include <vector>

#include "ply_slam/common/statistics.h"

namespace ply_slam {

// Latencies (s) of a stream that may never end: percentiles over the most recent `window`
// samples, the maximum and the count over the whole run.
class LatencyWindow {
 public:
  explicit LatencyWindow(size_t window = 10000) : window_(window) {}

  void add(double seconds) {
    if (recent_.size() >= window_) recent_.pop_front();
    recent_.push_back(seconds);
    max_ = count_ == 0 ? seconds : std::max(max_, seconds);
    ++count_;
  }
  // q in [0, 1] over the recent samples; 0 before the first.
  double percentile(double q) const {
    return ply_slam::percentile(std::vector<double>(recent_.begin(), recent_.end()), q, 0.0);
  }
  double max() const { return max_; }
  size_t count() const { return count_; }

 private:
  size_t window_;
  std::deque<double> recent_;
  double max_ = 0.0;
  size_t count_ = 0;
};

}  // namespace ply_slam
