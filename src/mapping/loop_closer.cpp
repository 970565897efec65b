#include "ply_slam/mapping/loop_closer.h"

#include <filesystem>
#include <vector>

#include "ply_slam/loop/vocabulary_identity.h"
#include "ply_slam/loop/vocabulary_path.h"

namespace ply_slam {
namespace {

std::map<long, int> covisibilityById(const KeyFrame& keyframe) {
  std::map<long, int> ids;
  for (const auto& [other, shared] : keyframe.covisibility) ids[other->id] = shared;
  return ids;
}

using KeyFramesById = std::map<long, const KeyFrame*>;

// The keyframe and those it shares landmarks with, into `out` by id (each once).
void addLinked(const KeyFrame& keyframe, KeyFramesById& out) {
  out.emplace(keyframe.id, &keyframe);
  for (const auto& [other, shared] : keyframe.covisibility) out.emplace(other->id, other);
}

KeyFramesById linkedTo(const KeyFrame& keyframe) {
  KeyFramesById linked;
  addLinked(keyframe, linked);
  return linked;
}

}  // namespace

LoopCloser::LoopCloser(LoopDetector detector, const PinholeCamera& camera,
                       const MapperOptions& options, const LandmarkFuser& fuser, Map& map)
    : detector_(std::move(detector)),
      builder_(options.lines, camera, options.loop, options.mask_dilation_px),
      corrector_(options.loop_correction, fuser, map),
      options_(options.loop_correction),
      orb_file_(
          std::filesystem::path(vocabularyPath(options.loop.orb_vocabulary, DescriptorKind::kOrb))
              .filename()),
      lbd_file_(
          std::filesystem::path(vocabularyPath(options.loop.lbd_vocabulary, DescriptorKind::kLbd))
              .filename()),
      map_(map) {}

bool LoopCloser::addKeyFrame(const KeyFrame& keyframe, LoopKeyFrame described) {
  std::lock_guard<std::mutex> lock(detector_mutex_);
  detector_.addKeyFrame(std::move(described));
  syncCovisibilityLocked(linkedTo(keyframe));
  return last_loop_keyframe_ < 0 ||
         keyframe.id - last_loop_keyframe_ > options_.min_keyframes_between;
}

std::optional<LoopDetection> LoopCloser::detect(long id) {
  std::lock_guard<std::mutex> lock(detector_mutex_);
  ++counts_.queries;
  LoopDetection detection = detector_.detect(id);
  counts_.detected += !detection.consistent.empty();
  if (!detection.loop) return std::nullopt;
  ++counts_.accepted;
  return detection;
}

std::optional<LoopCorrection> LoopCloser::close(KeyFrame& keyframe, const LoopDetection& detection,
                                                CorrectionPauses* pauses) {
  KeyFrame* candidate = keyFrame(*detection.loop);
  if (!candidate) return std::nullopt;  // culled since it joined the database
  const Eigen::Isometry3d& T_query_candidate = detection.geometry->T_query_candidate;
  if (!plausible(keyframe, *candidate, loopShift(keyframe, *candidate, T_query_candidate))) {
    std::lock_guard<std::mutex> lock(detector_mutex_);
    ++counts_.implausible;
    return std::nullopt;
  }
  LoopCorrection correction = corrector_.correct(keyframe, *candidate, T_query_candidate, pauses);
  std::lock_guard<std::mutex> lock(detector_mutex_);
  last_loop_keyframe_ = keyframe.id;
  ++counts_.corrected;
  // The fusion linked the two sides: they are no loop candidates of each other any more. Links
  // changed around each of the query's neighbours; every keyframe concerned is synced once.
  KeyFramesById changed;
  for (const auto& [kf, shared] : keyframe.covisibility) addLinked(*kf, changed);
  syncCovisibilityLocked(changed);
  return correction;
}

void LoopCloser::removeKeyFrame(long id) {
  std::lock_guard<std::mutex> lock(detector_mutex_);
  detector_.removeKeyFrame(id);
}

std::vector<long> LoopCloser::recognise(const cv::Mat& orb_descriptors, size_t max_results) const {
  std::lock_guard<std::mutex> lock(detector_mutex_);
  return detector_.recognise(orb_descriptors, max_results);
}

void LoopCloser::syncCovisibility(const KeyFrame& keyframe) {
  const KeyFramesById linked = linkedTo(keyframe);
  std::lock_guard<std::mutex> lock(detector_mutex_);
  syncCovisibilityLocked(linked);
}

void LoopCloser::syncCovisibilityLocked(const std::map<long, const KeyFrame*>& keyframes) {
  for (const auto& [id, kf] : keyframes) {
    try {
      detector_.setCovisibility(id, covisibilityById(*kf));
    } catch (const std::out_of_range&) {
      // A keyframe the database has not got: made before loop closure was switched on, or by
      // the tracker while the mapping thread works on an older one (it syncs when added).
    }
  }
}

bool LoopCloser::plausible(const KeyFrame& query, const KeyFrame& candidate,
                           const LoopShift& shift) const {
  // The path walked: keyframe centres from the candidate's to the query's, in order.
  double path_m = 0.0;
  const KeyFrame* previous = nullptr;
  for (const auto& kf : map_.keyFrames()) {
    if (kf->id < candidate.id || kf->id > query.id) continue;
    if (previous) path_m += (kf->T_wc().translation() - previous->T_wc().translation()).norm();
    previous = kf.get();
  }
  return shift.moved_m <= options_.max_drift_floor_m + options_.max_drift_fraction * path_m &&
         shift.turned_deg <=
             options_.max_rotation_drift_floor_deg + options_.max_rotation_drift_deg_per_m * path_m;
}

KeyFrame* LoopCloser::keyFrame(long id) const { return map_.keyFrame(id).get(); }

std::optional<KeyFramePlace> LoopCloser::place(const KeyFrame& keyframe) const {
  std::lock_guard<std::mutex> lock(detector_mutex_);
  const LoopKeyFrame* stored = nullptr;
  try {
    stored = &detector_.keyFrame(keyframe.id);
  } catch (const std::out_of_range&) {
    return std::nullopt;
  }
  KeyFramePlace place;
  // The database's keypoints are the keyframe's in order, those on moving objects left out.
  const auto& all = keyframe.features.undistorted;
  place.used_keypoints.assign(all.size(), 0);
  size_t next = 0;
  for (size_t i = 0; i < all.size() && next < stored->keypoints.size(); ++i)
    if (all[i] == stored->keypoints[next]) {
      place.used_keypoints[i] = 1;
      ++next;
    }
  place.lbd_descriptors = stored->lbd_descriptors.clone();
  place.instances = stored->instances;
  return place;
}

void LoopCloser::addLoadedKeyFrame(const KeyFrame& keyframe, const KeyFramePlace& place) {
  LoopKeyFrame kf;
  kf.id = keyframe.id;
  kf.stamp = keyframe.stamp;
  const FrameFeatures& f = keyframe.features;
  kf.orb_descriptors = cv::Mat(0, f.descriptors.cols, f.descriptors.type());
  for (size_t i = 0; i < f.size(); ++i) {
    if (!place.uses(i)) continue;
    kf.keypoints.push_back(f.undistorted[i]);
    kf.depth.push_back(f.depth[i]);
    kf.orb_descriptors.push_back(f.descriptors.row(static_cast<int>(i)));
  }
  kf.lbd_descriptors = place.lbd_descriptors.clone();
  kf.instances = place.instances;
  std::lock_guard<std::mutex> lock(detector_mutex_);
  detector_.addKeyFrame(std::move(kf));
}

MapVocabulary LoopCloser::orbVocabulary() const {
  return vocabularyIdentity(detector_.orbVocabulary(), orb_file_);
}

MapVocabulary LoopCloser::lbdVocabulary() const {
  return vocabularyIdentity(detector_.lbdVocabulary(), lbd_file_);
}

}  // namespace ply_slam
