#include "ply_slam/mapping/global_bundle_adjustment.h"

#include <map>
#include <set>

#include "ply_slam/common/stopwatch.h"

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
  carryAlong(map, window, before);
  const auto& [newest, newest_before] = before.back();
  return newest->T_wc() * newest_before.inverse();
}

void GlobalBundleAdjustment::carryAlong(
    Map& map, const BundleWindow& window,
    const std::vector<std::pair<KeyFrame*, Eigen::Isometry3d>>& before) {
  std::set<const KeyFrame*> solved;
  for (const auto& pose : window.poses)
    if (pose.local) solved.insert(pose.keyframe);
  std::set<long> carried;
  // How each keyframe moved; one made since the window was gathered follows its parent, else
  // the keyframe made before it.
  std::map<long, Eigen::Isometry3d> moved;
  Eigen::Isometry3d previous = Eigen::Isometry3d::Identity();
  for (const auto& [kf, T_wc] : before) {
    if (!solved.count(kf)) {
      const auto parent = kf->parent ? moved.find(kf->parent->id) : moved.end();
      kf->T_cw = ((parent != moved.end() ? parent->second : previous) * T_wc).inverse();
      carried.insert(kf->id);
    }
    previous = moved[kf->id] = kf->T_wc() * T_wc.inverse();
  }
  // Their landmarks (the window holds every landmark older keyframes made).
  for (const auto& point : map.mapPoints()) {
    if (point->bad || !carried.count(point->first_keyframe_id)) continue;
    const Eigen::Isometry3d& move = moved.at(point->first_keyframe_id);
    point->position = move * point->position;
    point->normal = move.linear() * point->normal;
  }
  for (const auto& line : map.mapLines()) {
    if (line->bad || !carried.count(line->first_keyframe_id)) continue;
    const Eigen::Isometry3d& move = moved.at(line->first_keyframe_id);
    line->start = move * line->start;
    line->end = move * line->end;
  }
}

}  // namespace ply_slam
