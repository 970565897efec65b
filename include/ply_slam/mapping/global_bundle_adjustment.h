#pragma once

#include <atomic>
#include <mutex>
#include <optional>
#include <thread>

#include "ply_slam/mapping/bundle_window.h"
#include "ply_slam/mapping/local_bundle_adjuster.h"

namespace ply_slam {

// The whole map's bundle adjustment after a loop closure, solved from a copy (BundleWindow) on
// a thread of its own, so that the mapping side goes on with new keyframes meanwhile; whoever
// started it writes the solution back (LocalBundleAdjuster::apply) once it is done. Starting
// another one (a newer loop) abandons a solve still running.
class GlobalBundleAdjustment {
 public:
  explicit GlobalBundleAdjustment(const LocalBundleAdjuster& adjuster) : adjuster_(adjuster) {}
  // Abandons a running solve.
  ~GlobalBundleAdjustment();
  GlobalBundleAdjustment(const GlobalBundleAdjustment&) = delete;
  GlobalBundleAdjustment& operator=(const GlobalBundleAdjustment&) = delete;

  // Abandons a running solve first (counted).
  void start(BundleWindow window);
  // The solved window, once, when the solve has ended; nothing while it runs or after it was
  // abandoned.
  std::optional<BundleWindow> takeSolved();
  // Blocks until the running solve ends.
  void wait();
  // A solved window waits to be taken (any thread may ask).
  bool hasSolved() const;
  // Writes a solved window back into the map (the map's lock held): LocalBundleAdjuster::apply,
  // then keyframes made since it was gathered move as their parent moved (else the keyframe
  // made before them), their own landmarks with them. Returns how the newest keyframe moved:
  // T_wc(after) = moved * T_wc(before).
  Eigen::Isometry3d writeBack(Map& map, const BundleWindow& window) const;
  int started() const { return started_; }
  int abandoned() const { return abandoned_; }
  double solveMs() const;  // of the solves that ended, in all

 private:
  void stop(bool abandon);

  const LocalBundleAdjuster& adjuster_;
  std::atomic<bool> abandon_{false};
  mutable std::mutex mutex_;
  std::optional<BundleWindow> solved_;  // guarded by mutex_
  double solve_ms_ = 0.0;               // guarded by mutex_
  int started_ = 0, abandoned_ = 0;     // the starting thread's
  std::thread thread_;
};

}  // namespace ply_slam
