#include "ply_slam/mapping/mapper.h"

#include <algorithm>
#include <chrono>
#include <thread>

#include "ply_slam/common/stopwatch.h"
#include "ply_slam/map/by_id.h"
#include "ply_slam/map/landmark_values.h"

namespace ply_slam {
namespace {

// A loop correction on the mapping thread lets the tracker at the map between its steps.
class LockPauses : public CorrectionPauses {
 public:
  LockPauses(std::unique_lock<std::mutex>& lock, std::function<void(const Eigen::Isometry3d&)> tell)
      : lock_(lock), tell_(std::move(tell)) {}

  void movedRigidly(const Eigen::Isometry3d& world_correction) override {
    tell_(world_correction);
    told_ = world_correction;
  }
  void pause() override {
    lock_.unlock();
    // A mutex is not handed over: without a moment's wait this thread takes it again before
    // the tracker, woken, gets to it.
    std::this_thread::sleep_for(std::chrono::microseconds(200));
    lock_.lock();
    held_ = Stopwatch();
  }
  void unlocked(const std::function<void()>& work) override {
    lock_.unlock();
    work();
    lock_.lock();
    held_ = Stopwatch();
  }
  // A pause once the lock has been held for `ms` since it was last taken.
  void pauseAfter(double ms) {
    if (held_.elapsedMs() >= ms) pause();
  }
  // What the tracker was told so far (the rigid move; identity when not used).
  const Eigen::Isometry3d& told() const { return told_; }

 private:
  std::unique_lock<std::mutex>& lock_;
  std::function<void(const Eigen::Isometry3d&)> tell_;
  Eigen::Isometry3d told_ = Eigen::Isometry3d::Identity();
  Stopwatch held_;  // since the lock was last taken (about: it is held when this is made)
};

// The longest the whole map's copy for the global bundle adjustment holds the lock at once on
// the mapping thread: a sixth of a 30 Hz frame period, so the tracker's wait stays well inside
// one frame (the copy took 47 ms in one piece on the 1 500-frame ring).
constexpr double kGatherHoldMs = 5.0;

// What local BA moved, as it is now (KeyFrameInsertionStats::adjusted): the window's own
// keyframes (by id: culling may have freed one) and its landmarks. Not the window taken again
// afterwards: fusion and culling change the new keyframe's best covisible keyframes.
MapUpdate adjustedBy(const std::vector<long>& keyframe_ids, const BundleWindow& window,
                     const Map& map, double stamp) {
  MapUpdate update;
  update.stamp = stamp;
  const auto keyframes = byId(map.keyFrames());
  std::set<long> lines;
  for (long id : keyframe_ids) {
    const auto kf = keyframes.find(id);
    if (kf == keyframes.end() || kf->second->bad) continue;
    update.keyframes.push_back(valuesOf(*kf->second));
    for (const auto& l : kf->second->map_lines)
      if (l && !l->bad && lines.insert(l->id).second) update.lines.push_back(valuesOf(*l));
  }
  for (const auto& p : window.landmarks)
    if (!p->bad) update.points.push_back(valuesOf(*p));
  return update;
}

}  // namespace

Mapper::Mapper(const PinholeCamera& camera, const MapperOptions& options, Map& map,
               bool wait_for_global_ba)
    : options_(options),
      map_(map),
      creator_(camera, options.max_point_depth, options.lines, map),
      fuser_(camera, options.orb, options.local),
      bundle_adjuster_(camera, options.local),
      point_culler_(options.culling.points),
      keyframe_culler_(options.culling.keyframes),
      wait_for_global_ba_(wait_for_global_ba),
      global_ba_(bundle_adjuster_) {
  if (options_.loop.enabled)
    loop_closer_ = std::make_unique<LoopCloser>(LoopDetector::fromOptions(camera, options_.loop),
                                                camera, options_, fuser_, map_);
}

KeyFrame* Mapper::spanningTreeParent(const KeyFrame& keyframe) const {
  // Never a newer one: a newer parent that later took this one as its own would make a cycle,
  // and erasing either would then leave a keyframe its own parent (a self edge in the pose graph).
  if (KeyFrame* best = keyframe.bestOlderCovisible()) return best;
  // A keyframe that shares nothing (after a loss) hangs off the one made before it.
  KeyFrame* before = nullptr;
  for (const auto& kf : map_.keyFrames())
    if (kf->id < keyframe.id) before = kf.get();
  return before;
}

KeyFrameInsertionStats Mapper::insertKeyFrame(const std::shared_ptr<KeyFrame>& keyframe,
                                              const KeepKeyFrames& keep) {
  KeyFrameInsertionStats stats;
  if (keyframe->id == 0) return stats;  // nothing to adjust against yet
  std::unique_lock<std::mutex> lock(map_.updateMutex());
  stats.global_ba_applied = writeBackSolvedGlobal().has_value();
  const std::vector<KeyFrame*> neighbours =
      keyframe->bestCovisible(options_.local.window_keyframes);
  stats.fused = fuser_.fuse(map_, *keyframe, neighbours);
  keyframe->parent = spanningTreeParent(*keyframe);
  BundleWindow window = bundle_adjuster_.gatherLocal(*keyframe);
  lock.unlock();
  bundle_adjuster_.solve(window);
  lock.lock();
  stats.bundle_adjustment = bundle_adjuster_.apply(map_, window);
  std::vector<long> adjusted_keyframes;
  for (const auto& pose : window.poses)
    if (pose.local) adjusted_keyframes.push_back(pose.keyframe->id);
  // Fusion and adjustment changed who sees what: the neighbourhood is taken again.
  stats.culled_points =
      point_culler_.cull(map_, *keyframe, keyframe->bestCovisible(options_.local.window_keyframes));
  stats.culled_keyframes = keyframe_culler_.cull(map_, *keyframe, keep ? keep() : std::set<long>{});
  if (loop_closer_)
    for (long id : stats.culled_keyframes) loop_closer_->removeKeyFrame(id);
  map_.removeBadLandmarks();
  stats.adjusted = adjustedBy(adjusted_keyframes, window, map_, keyframe->stamp);
  return stats;
}

std::optional<LoopCorrection> Mapper::closeLoop(KeyFrame& keyframe, const KeyFramePacket& packet) {
  if (!loop_closer_) return std::nullopt;
  LoopKeyFrame described = loop_closer_->describe(packet);
  std::unique_lock<std::mutex> lock(map_.updateMutex());
  if (!loop_closer_->addKeyFrame(keyframe, std::move(described))) return std::nullopt;
  lock.unlock();
  const std::optional<LoopDetection> detection = loop_closer_->detect(keyframe.id);
  lock.lock();
  if (!detection) return std::nullopt;
  // In line nobody waits for the map meanwhile: one hold, one move told (runs repeat).
  LockPauses pauses(lock, [this](const Eigen::Isometry3d& c) { tell(c); });
  std::optional<LoopCorrection> correction =
      loop_closer_->close(keyframe, *detection, wait_for_global_ba_ ? nullptr : &pauses);
  if (!correction) return correction;
  tell(correction->world_correction * pauses.told().inverse());  // what is left to tell
  const int iterations = options_.loop_correction.global_ba_iterations;
  if (iterations <= 0) return correction;
  Stopwatch watch;
  // On the mapping thread the copy of the map goes in pieces, the tracker between them.
  const std::function<void()> between = [&pauses] { pauses.pauseAfter(kGatherHoldMs); };
  global_ba_.start(
      bundle_adjuster_.gatherAll(map_, iterations, wait_for_global_ba_ ? nullptr : between));
  if (wait_for_global_ba_) {
    lock.unlock();
    global_ba_.wait();
    lock.lock();
    if (const auto refined = writeBackSolvedGlobal())
      correction->world_correction = *refined * correction->world_correction;
    correction->global_ba_ms = watch.elapsedMs();
  }
  correction->ms += watch.elapsedMs();
  return correction;
}

bool Mapper::applySolvedGlobalBundleAdjustment() {
  std::lock_guard<std::mutex> lock(map_.updateMutex());
  return writeBackSolvedGlobal().has_value();
}

GlobalBundleAdjustmentCounts Mapper::globalBundleAdjustmentCounts() const {
  return {global_ba_.started(), global_ba_applied_, global_ba_.abandoned(), global_ba_.solveMs()};
}

std::optional<Eigen::Isometry3d> Mapper::writeBackSolvedGlobal() {
  const std::optional<BundleWindow> solved = global_ba_.takeSolved();
  if (!solved) return std::nullopt;
  const Eigen::Isometry3d moved = global_ba_.writeBack(map_, *solved);
  map_.removeBadLandmarks();
  ++global_ba_applied_;
  tell(moved);
  return moved;
}

void Mapper::tell(const Eigen::Isometry3d& correction) const {
  if (listener_) listener_(correction);
}

MapUpdate Mapper::wholeMap() const {
  std::lock_guard<std::mutex> lock(map_.updateMutex());
  MapUpdate update;
  update.whole_map = true;
  for (const auto& kf : map_.keyFrames()) {
    update.stamp = std::max(update.stamp, kf->stamp);
    update.keyframes.push_back(valuesOf(*kf));
  }
  for (const auto& p : map_.mapPoints())
    if (!p->bad) update.points.push_back(valuesOf(*p));
  for (const auto& l : map_.mapLines())
    if (!l->bad) update.lines.push_back(valuesOf(*l));
  return update;
}

std::vector<long> Mapper::recognise(const cv::Mat& orb_descriptors, size_t max_results) const {
  if (!loop_closer_) return {};
  return loop_closer_->recognise(orb_descriptors, max_results);
}

std::map<long, KeyFramePlace> Mapper::places() const {
  std::map<long, KeyFramePlace> places;
  if (!loop_closer_) return places;
  for (const auto& kf : map_.keyFrames())
    if (auto place = loop_closer_->place(*kf)) places.emplace(kf->id, std::move(*place));
  return places;
}

void Mapper::addLoadedKeyFrames(const std::map<long, KeyFramePlace>& places) {
  if (!loop_closer_) return;
  const auto keyframes = map_.keyFrames();
  const KeyFramePlace none;  // a keyframe without a record: every keypoint, no lines
  for (const auto& kf : keyframes) {
    const auto it = places.find(kf->id);
    loop_closer_->addLoadedKeyFrame(*kf, it != places.end() ? it->second : none);
  }
  for (const auto& kf : keyframes) loop_closer_->syncCovisibility(*kf);
}

MapVocabulary Mapper::orbVocabulary() const {
  return loop_closer_ ? loop_closer_->orbVocabulary() : MapVocabulary{};
}

MapVocabulary Mapper::lbdVocabulary() const {
  return loop_closer_ ? loop_closer_->lbdVocabulary() : MapVocabulary{};
}

}  // namespace ply_slam
