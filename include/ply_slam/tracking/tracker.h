#pragma once

#include <functional>
#include <memory>
#include <string>
#include <unordered_set>
#include <vector>

#include "ply_slam/common/camera_velocity.h"
#include "ply_slam/common/pinhole_camera.h"
#include "ply_slam/features/line_matcher.h"
#include "ply_slam/features/line_options.h"
#include "ply_slam/features/orb_options.h"
#include "ply_slam/map/map.h"
#include "ply_slam/tracking/frame.h"
#include "ply_slam/tracking/landmark_sink.h"
#include "ply_slam/tracking/pose_optimizer.h"
#include "ply_slam/tracking/projection_matcher.h"
#include "ply_slam/tracking/tracking_options.h"

namespace ply_slam {

enum class TrackingState { kNotInitialised, kOk, kLost };
const char* toString(TrackingState state);

struct TrackingResult {
  TrackingState state = TrackingState::kNotInitialised;
  Eigen::Isometry3d T_cw = Eigen::Isometry3d::Identity();
  int inliers = 0;  // point inliers; at initialisation the points created (nothing to match yet)
  int line_inliers = 0;                    // line inliers (0 when lines are disabled)
  std::shared_ptr<KeyFrame> new_keyframe;  // set when this frame became a keyframe
  // It would have become one, but the mapping side is behind (keyframe_max_unmapped).
  bool keyframe_held_back = false;
  std::string method;  // how the pose was found: init, motion, pnp, reloc
};

// Frame-to-local-map tracking of RGB-D frames: constant-velocity prediction and projection
// matching, PnP-RANSAC when that fails, Ceres pose optimisation, local-map refinement,
// keyframe decision and relocalisation against keyframes after a loss. It reads the map and
// writes nothing to it: keyframes, landmarks and their statistics are the mapping side's,
// told through `mapping`.
class Tracker {
 public:
  // `orb`: the frames' pyramid; `lines`: tracking with lines (lines.enabled) and how they are
  // matched and weighted.
  Tracker(const PinholeCamera& camera, const TrackingOptions& tracking, const OrbOptions& orb,
          const LineOptions& lines, const Map& map, LandmarkSink& mapping);

  // Keyframe ids to relocalise against, most promising first (a place-recognition database).
  using PlaceCandidates = std::function<std::vector<long>(const Frame&)>;

  TrackingResult track(Frame& frame);
  // Once set, relocalisation tries only these keyframes; unset, every keyframe newest first.
  void setPlaceCandidates(PlaceCandidates candidates) { place_candidates_ = std::move(candidates); }
  // A loop closure moved the map: T_wc(after) = world_correction * T_wc(before) around the
  // current keyframe. The last frame moves the same, so the next prediction lands in the
  // corrected map.
  void applyCorrection(const Eigen::Isometry3d& world_correction);
  // A map loaded from a file: tracking starts lost, so that the first pose comes from
  // relocalisation in that map (never a new map at the identity).
  void startLost();
  // Localisation in a loaded map: track against it, add no keyframes (and so no landmarks) and
  // leave its geometry as it was saved.
  void setLocalisationOnly(bool only) { localisation_only_ = only; }
  // Keyframes handed to the mapping side that it has not finished, before each frame: while
  // there are more than keyframe_max_unmapped, tracking makes no new one.
  void setUnmappedKeyFrames(size_t count) { unmapped_keyframes_ = count; }
  TrackingState state() const { return state_; }
  // The camera's current velocity, null when unknown (start, after a loss).
  const CameraVelocity* velocity() const { return has_velocity_ ? &velocity_ : nullptr; }
  // The keyframe tracking refers to (the newest, or the one relocalised against); null before
  // initialisation. The mapping side must not cull it.
  const std::shared_ptr<KeyFrame>& referenceKeyFrame() const { return last_keyframe_; }

 private:
  bool initialise(Frame& frame);
  // The constant-velocity prediction of the pose at `stamp` (the last pose without a velocity).
  Eigen::Isometry3d predictedPose(double stamp) const;
  // The last tracked frame's pose moved on by velocity_ to `stamp`.
  Eigen::Isometry3d movedOn(double stamp) const;
  // The solved pose lies further from the constant-velocity prediction, or after a loss from
  // the last tracked pose, than a camera moves.
  bool farFromPrediction(const Frame& frame) const;
  bool trackWithMotionModel(Frame& frame);
  bool trackWithPnp(Frame& frame, const std::vector<std::shared_ptr<MapPoint>>& candidates);
  bool relocalise(Frame& frame);
  std::vector<std::shared_ptr<KeyFrame>> relocalisationOrder(const Frame& frame) const;
  int trackLocalMap(Frame& frame);
  void updateLocalMap(const Frame& frame);
  int optimizePose(Frame& frame);
  // Matches the frame's lines to the landmarks that are not bad, projected with frame.T_cw
  // (LineMatcher::matchSegments). Replaces the frame's line matches. Returns the matches.
  int matchLines(Frame& frame, const std::vector<std::shared_ptr<MapLine>>& candidates) const;
  bool needKeyFrame(const Frame& frame, int inliers) const;
  // A tracked frame keeps only its inlier matches.
  void unlinkOutliers(Frame& frame) const;

  const PinholeCamera camera_;
  const TrackingOptions options_;
  const LineOptions lines_;
  const Map& map_;
  LandmarkSink& mapping_;
  PoseOptimizer optimizer_;
  ProjectionMatcher matcher_;
  LineMatcher line_matcher_;

  TrackingState state_ = TrackingState::kNotInitialised;
  std::unique_ptr<Frame> last_frame_;
  CameraVelocity velocity_;  // between the last two tracked frames
  bool has_velocity_ = false;
  bool velocity_at_loss_ = false;  // velocity_ was valid when tracking was lost
  std::shared_ptr<KeyFrame> last_keyframe_;
  std::vector<std::shared_ptr<MapPoint>> local_points_;
  std::vector<std::shared_ptr<MapLine>> local_lines_;  // of the local keyframes
  // Of the frame being tracked, cleared per frame (landmarks hold no tracker state): what the
  // motion model projected (the local-map search skips it) and what the projection passes saw
  // in view (the mapping side counts it visible).
  std::unordered_set<const MapPoint*> projected_;
  std::vector<MapPoint*> in_view_;
  PlaceCandidates place_candidates_;
  bool localisation_only_ = false;
  size_t unmapped_keyframes_ = 0;
};

}  // namespace ply_slam
