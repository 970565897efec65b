#include "ply_slam/mapping/loop_closer.h"

namespace ply_slam {
namespace {

std::map<long, int> covisibilityById(const KeyFrame& keyframe) {
  std::map<long, int> ids;
  for (const auto& [other, shared] : keyframe.covisibility) ids[other->id] = shared;
  return ids;
}

}  // namespace

LoopCloser::LoopCloser(LoopDetector detector, const SystemConfig& config,
                       const LandmarkFuser& fuser, Map& map)
    : detector_(std::move(detector)),
      builder_(config.lines, config.camera, config.loop, config.dynamic.mask_dilation_px),
      corrector_(config.loop_correction, fuser, map),
      options_(config.loop_correction),
      map_(map) {}

std::optional<LoopCorrection> LoopCloser::addKeyFrame(KeyFrame& keyframe,
                                                      const KeyFramePacket& packet) {
  detector_.addKeyFrame(builder_.build(packet));
  syncCovisibility(keyframe);
  if (last_loop_keyframe_ >= 0 &&
      keyframe.id - last_loop_keyframe_ <= options_.min_keyframes_between)
    return std::nullopt;
  ++counts_.queries;
  const LoopDetection detection = detector_.detect(keyframe.id);
  counts_.detected += !detection.consistent.empty();
  if (!detection.loop) return std::nullopt;
  ++counts_.accepted;
  KeyFrame* candidate = keyFrame(*detection.loop);
  if (!candidate) return std::nullopt;  // culled since it joined the database
  const Eigen::Isometry3d& T_query_candidate = detection.geometry->T_query_candidate;
  if (!plausible(keyframe, *candidate, loopShift(keyframe, *candidate, T_query_candidate))) {
    ++counts_.implausible;
    return std::nullopt;
  }
  LoopCorrection correction = corrector_.correct(keyframe, *candidate, T_query_candidate);
  last_loop_keyframe_ = keyframe.id;
  ++counts_.corrected;
  // The fusion linked the two sides: they are no loop candidates of each other any more.
  for (const auto& [kf, shared] : keyframe.covisibility) syncCovisibility(*kf);
  return correction;
}

void LoopCloser::syncCovisibility(const KeyFrame& keyframe) {
  for (const auto& [other, shared] : keyframe.covisibility) {
    try {
      detector_.setCovisibility(other->id, covisibilityById(*other));
    } catch (const std::out_of_range&) {
      // A keyframe the detector never got (made before loop closure was switched on).
    }
  }
  detector_.setCovisibility(keyframe.id, covisibilityById(keyframe));
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

KeyFrame* LoopCloser::keyFrame(long id) const {
  for (const auto& kf : map_.keyFrames())
    if (kf->id == id) return kf.get();
  return nullptr;
}

}  // namespace ply_slam
