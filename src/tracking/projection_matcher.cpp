#include "ply_slam/tracking/projection_matcher.h"

#include "ply_slam/common/hamming.h"
#include "ply_slam/features/best_two.h"

#include <cmath>
#include <limits>

namespace ply_slam {

int descriptorDistance(const cv::Mat& a, const cv::Mat& b) {
  return hammingDistance(a.ptr<uint8_t>(), b.ptr<uint8_t>(), a.cols);
}

bool ProjectionMatcher::occluded(const Frame& frame, const Eigen::Vector2d& uv,
                                 const Eigen::Vector3d& pc,
                                 const ProjectionMatchParams& params) const {
  const cv::Mat& depth = frame.features.depth_image;
  if (depth.empty()) return false;
  const double z = depth_.atRaw(depth, depth_.distort(uv));
  // The same margin as the depth gate of a match: nearer than that is another surface.
  return z > 0.0 && z < pc.z() - (params.depth_gate * pc.z() + 0.05);
}

int ProjectionMatcher::match(Frame& frame, const std::vector<std::shared_ptr<MapPoint>>& points,
                             const std::vector<int>* levels, const ProjectionMatchParams& params,
                             std::vector<MapPoint*>& in_view,
                             std::unordered_set<const MapPoint*>* projected) const {
  const FrameFeatures& f = frame.features;
  const Eigen::Vector3d centre = frame.cameraCentre();
  // Best distance given to each feature in this pass: a better landmark takes a feature over.
  std::vector<int> assigned_distance(f.size(), std::numeric_limits<int>::max());
  std::vector<bool> assigned_here(f.size(), false);
  int matches = 0;

  for (size_t k = 0; k < points.size(); ++k) {
    const auto& point = points[k];
    if (!point || point->bad) continue;
    const Eigen::Vector3d pc = frame.T_cw * point->position;
    if (pc.z() <= 0.05) continue;
    const Eigen::Vector2d uv = camera_.project(pc);
    if (!camera_.inImage(uv)) continue;

    int level;
    if (levels) {
      level = (*levels)[k];
    } else {
      const Eigen::Vector3d ray = point->position - centre;
      const double distance = ray.norm();
      if (distance < 0.8 * point->min_distance || distance > 1.2 * point->max_distance) continue;
      if (ray.dot(point->normal) < 0.5 * distance) continue;  // seen from > 60° off its normal
      level = point->predictLevel(distance, log_scale_, num_levels_);
    }
    if (projected) projected->insert(point.get());
    if (occluded(frame, uv, pc, params)) continue;
    in_view.push_back(point.get());

    const double radius = params.radius_px * (*f.scales)[level];
    BestTwo found;
    for (size_t i : f.featuresInArea(uv.x(), uv.y(), radius, level - 1, level + 1)) {
      if (frame.map_points[i] && !assigned_here[i]) continue;  // matched by an earlier stage
      if (f.hasDepth(i) && std::abs(f.depth[i] - pc.z()) > params.depth_gate * pc.z() + 0.05)
        continue;
      found.offer(descriptorDistance(point->descriptor, f.descriptors.row(static_cast<int>(i))),
                  static_cast<long>(i));
    }
    if (!found.accept(params.max_distance, params.nn_ratio)) continue;
    const long best_index = found.index;
    const int best = found.best;
    if (best >= assigned_distance[best_index]) continue;
    if (!assigned_here[best_index]) ++matches;
    assigned_distance[best_index] = best;
    assigned_here[best_index] = true;
    frame.map_points[best_index] = point;
    frame.outlier[best_index] = false;
  }
  return matches;
}

}  // namespace ply_slam
