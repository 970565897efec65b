#include "ply_slam/tracking/tracker.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <opencv2/calib3d.hpp>
#include <opencv2/core/eigen.hpp>
#include <opencv2/features2d.hpp>
#include <unordered_set>

#include "ply_slam/common/angles.h"

namespace ply_slam {
namespace {

PoseOptimizerParams optimizerParams(const TrackingOptions& t) {
  PoseOptimizerParams p;
  p.chi2_pixel = t.chi2_outlier;
  p.chi2_depth = withDepthDof(t.chi2_outlier);
  p.rounds = t.optimisation_rounds;
  p.solver = t.pose_solver;
  return p;
}

// The landmarks (points or lines) of the keyframes, each once, not bad, in keyframe order.
template <typename Landmark>
std::vector<std::shared_ptr<Landmark>> landmarksOf(
    const std::vector<KeyFrame*>& keyframes,
    std::vector<std::shared_ptr<Landmark>> KeyFrame::*member) {
  std::vector<std::shared_ptr<Landmark>> out;
  std::unordered_set<const Landmark*> seen;
  for (const KeyFrame* kf : keyframes)
    for (const auto& l : kf->*member)
      if (l && !l->bad && seen.insert(l.get()).second) out.push_back(l);
  return out;
}

}  // namespace

const char* toString(TrackingState state) {
  switch (state) {
    case TrackingState::kNotInitialised:
      return "not_initialised";
    case TrackingState::kOk:
      return "ok";
    case TrackingState::kLost:
      return "lost";
  }
  return "?";
}

Tracker::Tracker(const PinholeCamera& camera, const TrackingOptions& tracking,
                 const OrbOptions& orb, const LineOptions& lines, const Map& map,
                 LandmarkSink& mapping)
    : camera_(camera),
      options_(tracking),
      lines_(lines),
      map_(map),
      mapping_(mapping),
      optimizer_(camera, optimizerParams(tracking)),
      matcher_(camera_, std::log(orb.scale_factor), orb.num_levels),
      line_matcher_(lines, camera) {}

TrackingResult Tracker::track(Frame& frame) {
  TrackingResult result;
  projected_.clear();
  in_view_.clear();
  if (state_ == TrackingState::kNotInitialised) {
    if (initialise(frame)) {
      result.method = "init";
      result.new_keyframe = last_keyframe_;
      result.inliers = frame.numMatches();
    }
  } else {
    bool ok = false;
    if (state_ == TrackingState::kOk) {
      ok = trackWithMotionModel(frame);
      result.method = "motion";
      if (!ok) {
        updateLocalMap(*last_frame_);
        ok = trackWithPnp(frame, local_points_);
        result.method = "pnp";
      }
    } else {
      ok = relocalise(frame);
      result.method = "reloc";
    }
    int inliers = 0;
    if (ok && state_ == TrackingState::kOk) {
      // The frame's own motion is now known far better than the prediction: undo the
      // exposure motion (rolling shutter, depth delay) with it and solve again.
      const CameraVelocity velocity =
          CameraVelocity::between(last_frame_->T_cw, frame.T_cw, frame.stamp - last_frame_->stamp);
      frame.features.correctMotion(camera_, &velocity);
      const int corrected = optimizePose(frame);  // first: it classifies the lines too
      ok = corrected + frame.numLineMatches() >= options_.min_tracked_points;
    }
    if (ok) {
      inliers = trackLocalMap(frame);
      // Line inliers count as tracked features too (none when lines are disabled).
      ok = inliers + frame.numLineMatches() >= options_.min_tracked_points &&
           !farFromPrediction(frame);
    }
    if (ok) {
      // A velocity needs two consecutive tracked frames close enough in time (none before the
      // first relocalisation in a loaded map).
      const double dt = last_frame_ ? frame.stamp - last_frame_->stamp : 0.0;
      has_velocity_ = state_ == TrackingState::kOk && dt > 0.0 && dt <= options_.max_velocity_gap_s;
      if (has_velocity_) velocity_ = CameraVelocity::between(last_frame_->T_cw, frame.T_cw, dt);
      state_ = TrackingState::kOk;
      unlinkOutliers(frame);
      // Localising in a loaded map leaves its geometry as it was saved.
      mapping_.recordTracked(frame, !localisation_only_);
      result.inliers = inliers;
      result.line_inliers = frame.numLineMatches();
      if (needKeyFrame(frame, inliers)) {
        result.keyframe_held_back =
            unmapped_keyframes_ > static_cast<size_t>(options_.keyframe_max_unmapped);
        if (!result.keyframe_held_back) {
          last_keyframe_ = mapping_.addKeyFrame(frame);
          result.new_keyframe = last_keyframe_;
        }
      }
    } else {
      // The velocity a tracked camera had when lost still bounds where it can be soon after.
      if (state_ == TrackingState::kOk) velocity_at_loss_ = has_velocity_;
      state_ = TrackingState::kLost;
      has_velocity_ = false;
    }
  }
  mapping_.countVisible(in_view_);
  frame.features.depth_image.release();  // keyframes and the last frame need no image
  result.state = state_;
  result.T_cw = frame.T_cw;
  if (state_ == TrackingState::kOk) last_frame_ = std::make_unique<Frame>(frame);
  return result;
}

void Tracker::startLost() {
  state_ = TrackingState::kLost;
  has_velocity_ = false;
  last_frame_.reset();
  last_keyframe_.reset();
}

void Tracker::applyCorrection(const Eigen::Isometry3d& world_correction) {
  if (last_frame_) last_frame_->T_cw = last_frame_->T_cw * world_correction.inverse();
}

Eigen::Isometry3d Tracker::predictedPose(double stamp) const {
  return has_velocity_ ? movedOn(stamp) : last_frame_->T_cw;
}

Eigen::Isometry3d Tracker::movedOn(double stamp) const {
  return velocity_.over(stamp - last_frame_->stamp) * last_frame_->T_cw;
}

bool Tracker::farFromPrediction(const Frame& frame) const {
  if (!last_frame_ || (state_ == TrackingState::kOk && !has_velocity_)) return false;
  const Eigen::Vector3d centre = frame.cameraCentre();  // where the solve put the camera
  const double dt = frame.stamp - last_frame_->stamp;
  // Tracking: the constant-velocity prediction. Relocalising within max_velocity_gap_s of the
  // last tracked frame: the prediction from the velocity it had (in 70 ms among people a
  // relocalisation put the camera 0.4-0.6 m off, where it cannot have gone).
  if (state_ == TrackingState::kOk || (velocity_at_loss_ && dt <= options_.max_velocity_gap_s))
    return (centre - movedOn(frame.stamp).inverse().translation()).norm() >
           options_.max_prediction_error;
  // Later: no further than a carried camera moves in the time (in an unmapped stretch of a
  // corridor a relocalisation put the camera 3 m back after 0.2 s).
  const double reach = options_.max_prediction_error + options_.max_camera_speed * dt;
  return (centre - last_frame_->cameraCentre()).norm() > reach;
}

bool Tracker::initialise(Frame& frame) {
  int with_depth = 0;
  for (size_t i = 0; i < frame.features.size(); ++i) with_depth += frame.features.hasDepth(i);
  if (with_depth < 2 * options_.min_tracked_points) return false;
  frame.T_cw = Eigen::Isometry3d::Identity();
  last_keyframe_ = mapping_.addKeyFrame(frame);
  state_ = TrackingState::kOk;
  has_velocity_ = false;
  return true;
}

bool Tracker::trackWithMotionModel(Frame& frame) {
  frame.T_cw = predictedPose(frame.stamp);
  // The last frame's landmarks, searched at the level they were seen at.
  std::vector<std::shared_ptr<MapPoint>> points;
  std::vector<int> levels;
  for (size_t i = 0; i < last_frame_->map_points.size(); ++i) {
    auto p = last_frame_->map_points[i];
    if (!p || last_frame_->outlier[i]) continue;
    while (p->bad && p->replaced_by) p = p->replaced_by;  // merged by the mapper meanwhile
    points.push_back(p);
    levels.push_back(last_frame_->features.level(i));
  }
  ProjectionMatchParams params;
  params.max_distance = options_.max_descriptor_distance;
  params.nn_ratio = options_.nn_ratio;
  // A pass replaces what an earlier one matched and saw in view: each landmark counts in view
  // once per frame.
  const auto search = [&](double radius_px) {
    frame.clearMatches();
    in_view_.clear();
    projected_.clear();
    params.radius_px = radius_px;
    return matcher_.match(frame, points, &levels, params, in_view_, &projected_);
  };
  int matches = search(options_.search_radius_px);
  if (matches < 2 * options_.min_tracked_points)
    matches = search(2.0 * options_.search_radius_px);  // fast motion: a wider window
  const int line_matches = lines_.enabled ? matchLines(frame, local_lines_) : 0;
  if (matches + line_matches < options_.min_tracked_points) return false;
  const int inliers = optimizePose(frame);  // first: it classifies the lines too
  return inliers + frame.numLineMatches() >= options_.min_tracked_points;
}

bool Tracker::trackWithPnp(Frame& frame, const std::vector<std::shared_ptr<MapPoint>>& candidates) {
  std::vector<std::shared_ptr<MapPoint>> points;
  cv::Mat descriptors;
  for (const auto& p : candidates) {
    if (!p || p->bad) continue;
    points.push_back(p);
    descriptors.push_back(p->descriptor);
  }
  if (static_cast<int>(points.size()) < options_.pnp_min_matches || frame.features.size() == 0)
    return false;

  cv::BFMatcher bf(cv::NORM_HAMMING);
  std::vector<std::vector<cv::DMatch>> knn;
  bf.knnMatch(frame.features.descriptors, descriptors, knn, 2);
  std::vector<cv::Point3f> object;
  std::vector<cv::Point2f> image;
  std::vector<std::pair<size_t, size_t>> pairs;  // (feature, point)
  for (const auto& m : knn) {
    if (m.empty() || m[0].distance > options_.max_descriptor_distance) continue;
    if (m.size() > 1 && m[0].distance > 0.8 * m[1].distance) continue;
    const auto& p = points[m[0].trainIdx]->position;
    const auto& uv = frame.features.undistorted[m[0].queryIdx];
    object.emplace_back(p.x(), p.y(), p.z());
    image.emplace_back(uv.x(), uv.y());
    pairs.emplace_back(m[0].queryIdx, m[0].trainIdx);
  }
  if (static_cast<int>(object.size()) < options_.pnp_min_matches) return false;

  cv::Mat rvec, tvec;
  std::vector<int> inliers;
  const bool solved = cv::solvePnPRansac(
      object, image, cv::Mat(camera_.K()), cv::noArray(), rvec, tvec, false,
      options_.pnp_iterations, options_.pnp_reprojection_px, 0.99, inliers, cv::SOLVEPNP_EPNP);
  if (!solved || static_cast<int>(inliers.size()) < options_.pnp_min_matches) return false;

  cv::Mat R;
  cv::Rodrigues(rvec, R);
  Eigen::Matrix3d R_eigen;
  Eigen::Vector3d t_eigen;
  cv::cv2eigen(R, R_eigen);
  cv::cv2eigen(tvec, t_eigen);
  frame.T_cw.linear() = R_eigen;
  frame.T_cw.translation() = t_eigen;
  frame.clearMatches();
  for (int k : inliers) frame.map_points[pairs[k].first] = points[pairs[k].second];
  return optimizePose(frame) >= options_.pnp_min_matches;
}

std::vector<std::shared_ptr<KeyFrame>> Tracker::relocalisationOrder(const Frame& frame) const {
  auto keyframes = map_.keyFrames();
  if (!place_candidates_) {
    // Newest keyframes first: after a short loss the camera is usually still near them.
    std::reverse(keyframes.begin(), keyframes.end());
    return keyframes;
  }
  std::map<long, std::shared_ptr<KeyFrame>> by_id;
  for (const auto& kf : keyframes)
    if (kf) by_id[kf->id] = kf;
  std::vector<std::shared_ptr<KeyFrame>> order;
  for (long id : place_candidates_(frame)) {
    auto it = by_id.find(id);
    if (it != by_id.end()) order.push_back(it->second);  // culled keyframes are skipped
  }
  return order;
}

bool Tracker::relocalise(Frame& frame) {
  for (const auto& kf : relocalisationOrder(frame)) {
    if (kf && trackWithPnp(frame, kf->map_points)) {
      last_keyframe_ = kf;
      return true;
    }
  }
  return false;
}

void Tracker::updateLocalMap(const Frame& frame) {
  // Keyframes that share landmarks with the frame, most shared first, plus the newest one.
  std::map<KeyFrame*, int> shared;
  for (size_t i = 0; i < frame.map_points.size(); ++i) {
    const auto& p = frame.map_points[i];
    if (!p || frame.outlier[i] || p->bad) continue;
    for (const auto& o : p->observers) ++shared[o.keyframe];
  }
  std::vector<std::pair<int, KeyFrame*>> ranked;
  for (const auto& [kf, n] : shared) ranked.emplace_back(n, kf);
  // Ties go to the older keyframe: the order must not depend on memory addresses.
  std::sort(ranked.begin(), ranked.end(), [](const auto& a, const auto& b) {
    return a.first != b.first ? a.first > b.first : a.second->id < b.second->id;
  });

  std::vector<KeyFrame*> chosen;
  for (const auto& [n, kf] : ranked) {
    if (static_cast<int>(chosen.size()) >= options_.local_map_keyframes) break;
    chosen.push_back(kf);
  }
  if (last_keyframe_ &&
      std::find(chosen.begin(), chosen.end(), last_keyframe_.get()) == chosen.end())
    chosen.push_back(last_keyframe_.get());

  local_points_ = landmarksOf(chosen, &KeyFrame::map_points);
  local_lines_.clear();
  if (lines_.enabled) local_lines_ = landmarksOf(chosen, &KeyFrame::map_lines);
}

int Tracker::matchLines(Frame& frame,
                        const std::vector<std::shared_ptr<MapLine>>& candidates) const {
  std::fill(frame.map_lines.begin(), frame.map_lines.end(), nullptr);
  std::fill(frame.line_outlier.begin(), frame.line_outlier.end(), false);
  std::vector<SegmentToMatch> segments;
  std::vector<size_t> index;  // the candidate of each segment
  for (size_t m = 0; m < candidates.size(); ++m) {
    const MapLine& l = *candidates[m];
    if (l.bad) continue;
    segments.push_back({l.start, l.end, l.descriptor.ptr()});
    index.push_back(m);
  }
  const std::vector<LineMatch> matches =
      line_matcher_.matchSegments(segments, frame.lines, frame.T_cw);
  for (const LineMatch& m : matches) frame.map_lines[m.b] = candidates[index[m.a]];
  return static_cast<int>(matches.size());
}

int Tracker::trackLocalMap(Frame& frame) {
  updateLocalMap(frame);
  ProjectionMatchParams params;
  params.radius_px = options_.search_radius_px / 3.0;  // the pose is already refined
  params.max_distance = options_.max_descriptor_distance;
  params.nn_ratio = options_.nn_ratio;
  unlinkOutliers(frame);  // outliers of the first estimate may match a better landmark
  std::vector<std::shared_ptr<MapPoint>> candidates;
  candidates.reserve(local_points_.size());
  for (const auto& p : local_points_)
    if (!projected_.count(p.get())) candidates.push_back(p);
  matcher_.match(frame, candidates, nullptr, params, in_view_);
  if (lines_.enabled) matchLines(frame, local_lines_);  // again, with the refined pose
  return optimizePose(frame);
}

int Tracker::optimizePose(Frame& frame) {
  std::vector<PointObservation> observations;
  std::vector<size_t> index;
  const auto& f = frame.features;
  for (size_t i = 0; i < frame.map_points.size(); ++i) {
    if (!frame.map_points[i]) continue;
    PointObservation o;
    o.world = frame.map_points[i]->position;
    o.pixel = f.undistorted[i];
    o.pixel_sigma = f.scale(i);
    if (f.hasDepth(i)) {
      o.depth = f.depth[i];
      o.depth_sigma = std::sqrt(camera_.depth_noise.varianceAgainstMap(o.depth));
    }
    observations.push_back(o);
    index.push_back(i);
  }
  std::vector<bool> inlier;
  if (!lines_.enabled) {
    const int n = optimizer_.optimize(observations, frame.T_cw, inlier);
    for (size_t k = 0; k < index.size(); ++k) frame.outlier[index[k]] = !inlier[k];
    return n;
  }
  std::vector<LineObservation> lines;
  std::vector<size_t> line_index;
  for (size_t i = 0; i < frame.map_lines.size(); ++i) {
    const auto& l = frame.map_lines[i];
    if (!l) continue;
    LineObservation o;
    o.start = l->start;
    o.end = l->end;
    o.line = frame.lines.lines[i].line();
    o.pixel_sigma = lines_.residual_sigma_px;
    lines.push_back(o);
    line_index.push_back(i);
  }
  std::vector<bool> line_inlier;
  const double weight = lineBalanceFactor(lines_.balance, static_cast<int>(observations.size()));
  const int n = optimizer_.optimize(observations, lines, weight, frame.T_cw, inlier, line_inlier);
  for (size_t k = 0; k < index.size(); ++k) frame.outlier[index[k]] = !inlier[k];
  for (size_t k = 0; k < line_index.size(); ++k)
    frame.line_outlier[line_index[k]] = !line_inlier[k];
  return n;
}

void Tracker::unlinkOutliers(Frame& frame) const {
  for (size_t i = 0; i < frame.map_points.size(); ++i)
    if (frame.outlier[i]) frame.map_points[i] = nullptr;
  for (size_t i = 0; i < frame.map_lines.size(); ++i)
    if (frame.line_outlier[i]) frame.map_lines[i] = nullptr;
}

bool Tracker::needKeyFrame(const Frame& frame, int inliers) const {
  if (localisation_only_) return false;
  if (!last_keyframe_) return true;
  const auto& t = options_;
  if (frame.id - last_keyframe_->frame_id >= t.keyframe_max_frames) return true;
  // Landmarks seen from two keyframes are the established ones the frame should keep seeing.
  if (inliers < t.keyframe_min_ratio * last_keyframe_->trackedPoints(2)) return true;
  const Eigen::Isometry3d motion = last_keyframe_->T_cw * frame.T_cw.inverse();
  return motion.translation().norm() > t.keyframe_translation ||
         rotationAngleDeg(motion.linear()) > t.keyframe_rotation_deg;
}

}  // namespace ply_slam
