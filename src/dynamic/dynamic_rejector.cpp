#include "ply_slam/dynamic/dynamic_rejector.h"

#include <algorithm>
#include <limits>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

#include "ply_slam/common/hamming.h"
#include "ply_slam/dynamic/depth_surfaces.h"
#include "ply_slam/features/best_two.h"
#include "ply_slam/features/depth_slope.h"

namespace ply_slam {
namespace {

constexpr double kRatio = 0.8;  // best / second-best descriptor distance between frames
constexpr uchar kNoMotion = DynamicRejection::kNoMotion;

bool onMask(const cv::Mat& mask, double u, double v) {
  const int x = std::clamp(cvRound(u), 0, mask.cols - 1);
  const int y = std::clamp(cvRound(v), 0, mask.rows - 1);
  return mask.at<uchar>(y, x) != 0;
}

}  // namespace

DynamicRejector::DynamicRejector(const DynamicOptions& params, const PinholeCamera& camera)
    : params_(params),
      mode_(params.mode),
      camera_(camera),
      filter_(camera, params.filter),
      active_(params.active_classes.begin(), params.active_classes.end()),
      passive_(params.passive_classes.begin(), params.passive_classes.end()) {}

ClassMotion DynamicRejector::motionOf(const std::string& class_name) const {
  if (active_.count(class_name)) return ClassMotion::kActive;
  if (passive_.count(class_name)) return ClassMotion::kPassive;
  return ClassMotion::kStatic;
}

void DynamicRejector::remember(const FrameFeatures& current, double stamp,
                               const DynamicRejection& rejection) {
  if (mode_ != DynamicMode::kGeometric && mode_ != DynamicMode::kFull) return;
  surface_age_ = rejection.surface_age;
  surface_candidates_ = rejection.surface_candidates;
  earlier_.push_back({stamp, current, depthSlopes(current)});
  earlier_.back().features.depth_image.release();
  while (static_cast<int>(earlier_.size()) > params_.baseline_frames) earlier_.pop_front();
}

std::vector<FeatureCorrespondence> DynamicRejector::correspondences(
    const Earlier& earlier, const FrameFeatures& current,
    const std::optional<Eigen::Isometry3d>& T_cur_prev, std::vector<size_t>& feature_of) const {
  const FrameFeatures& prev = earlier.features;
  std::vector<FeatureCorrespondence> out;
  feature_of.clear();
  if (prev.size() == 0 || current.size() == 0) return out;
  // Without a prediction the camera may have moved further: search wider.
  const double radius = T_cur_prev ? params_.match_radius_px : 2.0 * params_.match_radius_px;
  struct Best {
    int distance = std::numeric_limits<int>::max();
    size_t previous = 0;
  };
  std::vector<Best> best(current.size());
  for (size_t j = 0; j < prev.size(); ++j) {
    if (!prev.hasDepth(j)) continue;
    const Eigen::Vector3d p_prev = camera_.backProject(prev.undistorted[j], prev.depth[j]);
    const Eigen::Vector3d p = T_cur_prev ? Eigen::Vector3d(*T_cur_prev * p_prev) : p_prev;
    if (p.z() <= 0) continue;
    const Eigen::Vector2d uv = camera_.project(p);
    const int level = prev.level(j);
    BestTwo two;
    for (size_t i : current.featuresInArea(uv.x(), uv.y(), radius, level - 1, level + 1))
      two.offer(
          hammingDistance(prev.descriptors.ptr(static_cast<int>(j)),
                          current.descriptors.ptr(static_cast<int>(i)), prev.descriptors.cols),
          static_cast<long>(i));
    if (!two.accept(params_.max_descriptor_distance, kRatio)) continue;
    const auto i1 = static_cast<size_t>(two.index);
    if (two.best < best[i1].distance) best[i1] = {two.best, j};
  }
  for (size_t i = 0; i < current.size(); ++i) {
    if (best[i].distance == std::numeric_limits<int>::max() || !current.hasDepth(i)) continue;
    const size_t j = best[i].previous;
    out.push_back({current.undistorted[i], camera_.backProject(prev.undistorted[j], prev.depth[j]),
                   camera_.backProject(current.undistorted[i], current.depth[i]), earlier.slopes[j],
                   depthSlopeOf(current, i)});
    feature_of.push_back(i);
  }
  return out;
}

cv::Mat DynamicRejector::unionMask(const std::vector<Instance>& instances,
                                   const std::set<int>& ids) const {
  cv::Mat mask;
  for (const auto& instance : instances) {
    if (!ids.count(instance.id)) continue;
    if (mask.empty()) mask = cv::Mat::zeros(instance.mask.size(), CV_8UC1);
    mask |= instance.mask;
  }
  return mask.empty() ? mask : dilated(mask);
}

cv::Mat DynamicRejector::dilated(const cv::Mat& mask) const {
  const int r = params_.mask_dilation_px;
  if (r <= 0) return mask;
  cv::Mat out;
  cv::dilate(mask, out,
             cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(2 * r + 1, 2 * r + 1)));
  return out;
}

void DynamicRejector::labelByInstances(const FrameFeatures& current,
                                       const std::vector<size_t>& feature_of,
                                       const std::vector<Instance>& instances,
                                       std::vector<int>& label,
                                       std::map<int, ClassMotion>& motion) const {
  for (const auto& instance : instances) motion[instance.id] = motionOf(instance.class_name);
  // A feature takes the first instance whose mask holds it: the segmenter's detections come
  // before those InstanceMemory carried on, so what this frame shows wins over a guess.
  for (size_t k = 0; k < feature_of.size(); ++k) {
    const cv::Point2f& pt = current.keypoints[feature_of[k]].pt;
    for (const auto& instance : instances)
      if (onMask(instance.mask, pt.x, pt.y)) {
        label[k] = instance.id;
        break;
      }
  }
}

DynamicRejector::SurfaceHistory DynamicRejector::labelBySurfaces(
    const DepthSurfaces& surfaces, const FrameFeatures& current,
    const std::vector<size_t>& feature_of, std::vector<int>& label,
    std::map<int, ClassMotion>& motion) const {
  std::map<int, int> matched;
  for (size_t k = 0; k < feature_of.size(); ++k) {
    const int surface = surfaces.at(current.keypoints[feature_of[k]].pt);
    if (surface == 0) continue;
    label[k] = surface;
    ++matched[label[k]];
  }
  // A surface with fewer matched features than a person needs to be judged is left to the
  // feature-wise check: one stray vote would otherwise drop it whole.
  for (size_t k = 0; k < feature_of.size(); ++k)
    if (label[k] != 0 && matched[label[k]] < params_.filter.min_judged_features) label[k] = 0;
  // A surface that lies mostly where a surface was measured moving within carry_frames is
  // presumed moving still (a person who stops for a moment is still a person) and judged as
  // one (moved when a few of its features did); a surface not seen moving needs most of its
  // features to have moved.
  SurfaceHistory history{agedOn(surfaces, surface_age_), agedOn(surfaces, surface_candidates_)};
  for (const auto& [id, n] : matched)
    if (n >= params_.filter.min_judged_features)
      motion[id] = history.presumed.count(id) || history.seen_moving.count(id)
                       ? ClassMotion::kActive
                       : ClassMotion::kPassive;
  return history;
}

bool DynamicRejector::movedApart(const std::vector<FeatureCorrespondence>& matched,
                                 const std::vector<int>& label, int id,
                                 const DelaunayConsistency::StaticFit& fit) const {
  std::vector<FeatureCorrespondence> body;
  for (size_t k = 0; k < matched.size(); ++k)
    if (label[k] == id) body.push_back(matched[k]);
  return filter_.consistency().movedApart(body, fit);
}

std::map<int, uchar> DynamicRejector::agedOn(const DepthSurfaces& surfaces,
                                             const cv::Mat& ages) const {
  std::map<int, uchar> aged;
  if (ages.empty()) return aged;
  const std::vector<DepthSurfaces::Overlap> overlap = surfaces.overlap(ages, kNoMotion);
  for (int s = 1; s <= surfaces.count(); ++s)
    if (overlap[s - 1].share > 0.5 && overlap[s - 1].median < params_.carry_frames)
      aged[s] = static_cast<uchar>(overlap[s - 1].median + 1);
  return aged;
}

bool DynamicRejector::minority(const std::vector<int>& label, int id,
                               const DelaunayConsistency::StaticFit& fit) const {
  const auto n = std::count(label.begin(), label.end(), id);
  return static_cast<double>(n) < params_.filter.consistency.minority_share * fit.inliers;
}

void DynamicRejector::judgeSurfaces(const DepthSurfaces& surfaces, const DynamicDecision& d,
                                    const std::vector<FeatureCorrespondence>& matched,
                                    const std::vector<int>& label, SurfaceHistory history,
                                    DynamicRejection& r) const {
  // Moving: judged so by its features, and its own motion apart from the camera's. A surface
  // not presumed moving and not clearly smaller than the static scene it was judged against
  // must be seen so twice within carry_frames: one blurred frame in a fast turn can make a
  // whole wall look moved against a wrong fit; a person walking moves on.
  std::map<int, uchar>& candidates = history.seen_moving;  // aged on, those seen again move
  for (int s : d.dynamic_instances) {
    if (d.static_fit && !movedApart(matched, label, s, *d.static_fit)) continue;
    if (history.presumed.count(s) || candidates.count(s) ||
        (d.static_fit && minority(label, s, *d.static_fit))) {
      history.presumed[s] = 0;
      candidates.erase(s);
    } else {
      candidates[s] = 0;
    }
  }
  if (!history.presumed.empty()) r.surface_age = surfaces.paint(history.presumed, kNoMotion);
  if (!candidates.empty()) r.surface_candidates = surfaces.paint(candidates, kNoMotion);
}

DynamicRejection DynamicRejector::decide(const FrameFeatures& current, double stamp,
                                         const std::vector<Instance>& instances,
                                         const CameraVelocity* velocity,
                                         const std::set<int>& presumed) const {
  DynamicRejection r;
  r.fate.assign(current.size(), FeatureFate::kKept);
  if (mode_ == DynamicMode::kOff) return r;
  if (mode_ == DynamicMode::kSemantic) {
    for (const auto& instance : instances)
      if (motionOf(instance.class_name) == ClassMotion::kActive)
        r.dynamic_instances.insert(instance.id);
  } else {
    judgeByMotion(current, stamp, instances, velocity, presumed, r);
  }
  dropWholeObjects(current, instances, r);
  return r;
}

void DynamicRejector::judgeByMotion(const FrameFeatures& current, double stamp,
                                    const std::vector<Instance>& instances,
                                    const CameraVelocity* velocity, const std::set<int>& presumed,
                                    DynamicRejection& r) const {
  std::vector<size_t> feature_of;
  std::vector<FeatureCorrespondence> matched;
  std::optional<Eigen::Isometry3d> T_cur_prev;
  if (!earlier_.empty()) {
    const Earlier& earlier = earlier_.front();
    if (velocity && stamp > earlier.stamp) T_cur_prev = velocity->over(stamp - earlier.stamp);
    matched = correspondences(earlier, current, T_cur_prev, feature_of);
  }
  // Full mode labels features by the segmenter's instances, geometric mode by the depth
  // image's surfaces, judged as objects of unknown class.
  std::vector<int> label(matched.size(), 0);
  std::map<int, ClassMotion> motion;
  std::optional<DepthSurfaces> surfaces;
  SurfaceHistory history;
  if (mode_ == DynamicMode::kFull) {
    labelByInstances(current, feature_of, instances, label, motion);
  } else if (!current.depth_image.empty()) {
    surfaces.emplace(current.depth_image, camera_.depth_noise);
    history = labelBySurfaces(*surfaces, current, feature_of, label, motion);
  }
  const DynamicDecision d = filter_.decide(matched, label, motion, camera_.width, camera_.height,
                                           T_cur_prev ? &*T_cur_prev : nullptr);
  for (size_t k = 0; k < matched.size(); ++k)
    if (d.weight[k] > params_.filter.weight_threshold)
      r.fate[feature_of[k]] = FeatureFate::kGeometric;
  if (surfaces) {
    judgeSurfaces(*surfaces, d, matched, label, std::move(history), r);
    return;
  }
  r.dynamic_instances = d.dynamic_instances;
  r.measured_instances = d.measured;
  for (const auto& [id, kind] : motion)
    if (kind == ClassMotion::kActive && presumed.count(id)) r.dynamic_instances.insert(id);
}

void DynamicRejector::dropWholeObjects(const FrameFeatures& current,
                                       const std::vector<Instance>& instances,
                                       DynamicRejection& r) const {
  // Whole instances are the labels' judgement, whole surfaces the geometry's.
  const bool by_surfaces = !r.surface_age.empty();
  r.dynamic_mask =
      by_surfaces ? dilated(r.surface_age != kNoMotion) : unionMask(instances, r.dynamic_instances);
  if (r.dynamic_mask.empty()) return;
  const FeatureFate whole = by_surfaces ? FeatureFate::kGeometric : FeatureFate::kSemantic;
  for (size_t i = 0; i < current.size(); ++i)
    if (r.fate[i] == FeatureFate::kKept &&
        onMask(r.dynamic_mask, current.keypoints[i].pt.x, current.keypoints[i].pt.y))
      r.fate[i] = whole;
}

std::vector<bool> DynamicRejector::linesTouching(const std::vector<LineFeature>& lines,
                                                 const cv::Mat& mask) {
  std::vector<bool> touching(lines.size(), false);
  if (mask.empty()) return touching;
  for (size_t i = 0; i < lines.size(); ++i)
    touching[i] = onMask(mask, lines[i].raw_start.x(), lines[i].raw_start.y()) ||
                  onMask(mask, lines[i].raw_end.x(), lines[i].raw_end.y());
  return touching;
}

}  // namespace ply_slam
