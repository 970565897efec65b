#include "ply_slam/ros/unpaired_images.h"

#include <algorithm>

namespace ply_slam {

std::optional<double> UnpairedImages::arrived(double stamp) {
  waiting_.push_back(stamp);
  if (waiting_.size() <= max_waiting_) return std::nullopt;
  const double oldest = waiting_.front();
  waiting_.pop_front();
  return oldest;
}

std::vector<double> UnpairedImages::paired(double stamp) {
  const auto used = std::find(waiting_.begin(), waiting_.end(), stamp);
  std::vector<double> unpaired;
  // Arrived later than the paired one, or newer: it may still be paired.
  std::deque<double> kept;
  for (auto it = waiting_.begin(); it != waiting_.end(); ++it) {
    if (it == used) continue;
    if (it < used && *it < stamp)
      unpaired.push_back(*it);
    else
      kept.push_back(*it);
  }
  waiting_.swap(kept);
  return unpaired;
}

}  // namespace ply_slam
