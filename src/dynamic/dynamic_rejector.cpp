#include "ply_slam/dynamic/dynamic_rejector.h"

#include <algorithm>
#include <limits>
#include <opencv2/core.hpp>
#include <opencv2/core/hal/hal.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

#include "ply_slam/features/best_two.h"

namespace ply_slam {
namespace {

constexpr double kRatio = 0.8;  // best / second-best descriptor distance between frames

bool onMask(const cv::Mat& mask, double u, double v) {
  const int x = std::clamp(cvRound(u), 0, mask.cols - 1);
  const int y = std::clamp(cvRound(v), 0, mask.rows - 1);
  return mask.at<uchar>(y, x) != 0;
}

}  // namespace

DynamicMode parseDynamicMode(const std::string& mode) {
  if (mode == "off") return DynamicMode::kOff;
  if (mode == "geometric") return DynamicMode::kGeometric;
  if (mode == "semantic") return DynamicMode::kSemantic;
  if (mode == "full") return DynamicMode::kFull;
  throw std::invalid_argument("dynamic mode '" + mode + "' (off, geometric, semantic or full)");
}

DynamicRejector::DynamicRejector(const DynamicParams& params, const PinholeCamera& camera)
    : params_(params),
      mode_(parseDynamicMode(params.mode)),
      camera_(camera),
      filter_(camera, params.filter),
      active_(params.active_classes.begin(), params.active_classes.end()),
      passive_(params.passive_classes.begin(), params.passive_classes.end()) {}

ClassMotion DynamicRejector::motionOf(const std::string& class_name) const {
  if (active_.count(class_name)) return ClassMotion::kActive;
  if (passive_.count(class_name)) return ClassMotion::kPassive;
  return ClassMotion::kStatic;
}

void DynamicRejector::remember(const FrameFeatures& current, double stamp) {
  if (mode_ != DynamicMode::kGeometric && mode_ != DynamicMode::kFull) return;
  earlier_.push_back({stamp, current});
  earlier_.back().features.depth_image.release();
  while (static_cast<int>(earlier_.size()) > params_.baseline_frames) earlier_.pop_front();
}

std::vector<FeatureCorrespondence> DynamicRejector::correspondences(
    const FrameFeatures& prev, const FrameFeatures& current,
    const std::optional<Eigen::Isometry3d>& T_cur_prev, std::vector<size_t>& feature_of) const {
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
          cv::hal::normHamming(prev.descriptors.ptr(static_cast<int>(j)),
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
                   camera_.backProject(current.undistorted[i], current.depth[i])});
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
  const int r = params_.mask_dilation_px;
  if (!mask.empty() && r > 0)
    cv::dilate(mask, mask,
               cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(2 * r + 1, 2 * r + 1)));
  return mask;
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
    std::vector<size_t> feature_of;
    std::vector<FeatureCorrespondence> matched;
    std::optional<Eigen::Isometry3d> T_cur_prev;
    if (!earlier_.empty()) {
      const Earlier& earlier = earlier_.front();
      if (velocity && stamp > earlier.stamp) T_cur_prev = velocity->over(stamp - earlier.stamp);
      matched = correspondences(earlier.features, current, T_cur_prev, feature_of);
    }
    // Labels only in full mode: geometric mode judges features alone.
    std::vector<int> label(matched.size(), 0);
    std::map<int, ClassMotion> motion;
    if (mode_ == DynamicMode::kFull) {
      for (const auto& instance : instances) motion[instance.id] = motionOf(instance.class_name);
      for (size_t k = 0; k < matched.size(); ++k) {
        const cv::Point2f& pt = current.keypoints[feature_of[k]].pt;
        for (const auto& instance : instances)
          if (onMask(instance.mask, pt.x, pt.y)) {
            label[k] = instance.id;
            break;
          }
      }
    }
    const DynamicDecision d = filter_.decide(matched, label, motion, camera_.width, camera_.height,
                                             T_cur_prev ? &*T_cur_prev : nullptr);
    for (size_t k = 0; k < matched.size(); ++k)
      if (d.weight[k] > params_.filter.weight_threshold)
        r.fate[feature_of[k]] = FeatureFate::kGeometric;
    r.dynamic_instances = d.dynamic_instances;
    r.measured_instances = d.measured;
    // Semantic mode has every active instance dynamic already.
    for (const auto& [id, kind] : motion)
      if (kind == ClassMotion::kActive && presumed.count(id)) r.dynamic_instances.insert(id);
  }
  r.dynamic_mask = unionMask(instances, r.dynamic_instances);
  if (!r.dynamic_mask.empty())
    for (size_t i = 0; i < current.size(); ++i)
      if (r.fate[i] == FeatureFate::kKept &&
          onMask(r.dynamic_mask, current.keypoints[i].pt.x, current.keypoints[i].pt.y))
        r.fate[i] = FeatureFate::kSemantic;
  return r;
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
