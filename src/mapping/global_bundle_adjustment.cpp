#include "ply_slam/mapping/global_bundle_adjustment.h"

#include <map>
#include <set>

#include "ply_slam/common/stopwatch.h"
#include "ply_slam/mapping/carry_along.h"

namespace ply_slam {

GlobalBundleAdjustment::~GlobalBundleAdjustment() { stop(true); }

void GlobalBundleAdjustment::stop(bool abandon) {
  if (!thread_.joinable()) return;
  abandon_ = abandon;
  thread_.join();
  abandon_ = false;
}

void GlobalBundleAdjustment::start(BundleWindow window) {
  if (thread_.joinable()) {
    stop(true);
    std::lock_guard<std::mutex> lock(mutex_);
    if (!solved_) ++abandoned_;  // still running when the new loop came
    solved_.reset();
  }
  ++started_;
  thread_ = std::thread([this, window = std::move(window)]() mutable {
    Stopwatch watch;
    const bool finished = adjuster_.solve(window, &abandon_);
    std::lock_guard<std::mutex> lock(mutex_);
    solve_ms_ += watch.elapsedMs();
    if (finished) solved_ = std::move(window);
  });
}

std::optional<BundleWindow> GlobalBundleAdjustment::takeSolved() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (!solved_) return std::nullopt;
  }
  stop(false);  // it has ended: only the join is left
  std::lock_guard<std::mutex> lock(mutex_);
  std::optional<BundleWindow> solved = std::move(solved_);
  solved_.reset();
  return solved;
}

void GlobalBundleAdjustment::wait() { stop(false); }

bool GlobalBundleAdjustment::hasSolved() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return solved_.has_value();
}

double GlobalBundleAdjustment::solveMs() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return solve_ms_;
}

Eigen::Isometry3d GlobalBundleAdjustment::writeBack(Map& map, const BundleWindow& window) const {
  std::vector<std::pair<KeyFrame*, Eigen::Isometry3d>> before;  // T_wc, in id order
  for (const auto& kf : map.keyFrames()) before.emplace_back(kf.get(), kf->T_wc());
  adjuster_.apply(map, window);
  std::set<const KeyFrame*> solved;
  for (const auto& pose : window.poses)
    if (pose.local) solved.insert(pose.keyframe);
  carryAlong(map, solved, before);
  const auto& [newest, newest_before] = before.back();
  return newest->T_wc() * newest_before.inverse();
}

}  // namespace ply_slam
