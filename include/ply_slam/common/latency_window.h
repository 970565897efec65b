#pragma once

#include <algorithm>
#include <cstddef>
#include <deque>
#include <vector>

#include "ply_slam/common/statistics.h"

namespace ply_slam {

// Latencies (s) of a stream that may never end: percentiles over the most recent `window`
// samples (1000: the last ~33 s of a 30 Hz camera; read after every frame, so kept small), the
// maximum and the count over the whole run.
class LatencyWindow {
 public:
  explicit LatencyWindow(size_t window = 1000) : window_(window) {}

  void add(double seconds) {
    if (recent_.size() >= window_) recent_.pop_front();
    recent_.push_back(seconds);
    max_ = count_ == 0 ? seconds : std::max(max_, seconds);
    ++count_;
  }
  // q in [0, 1] over the recent samples; 0 before the first.
  double percentile(double q) const { return percentiles({q})[0]; }
  // Several at once, from one copy of the window.
  std::vector<double> percentiles(const std::vector<double>& qs) const {
    const std::vector<double> recent(recent_.begin(), recent_.end());
    std::vector<double> out;
    for (double q : qs) out.push_back(ply_slam::percentile(recent, q, 0.0));
    return out;
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
