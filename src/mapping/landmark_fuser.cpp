#include "ply_slam/mapping/landmark_fuser.h"

#include <cmath>
#include <limits>
#include <unordered_set>

#include "ply_slam/common/chi_square.h"
#include "ply_slam/tracking/projection_matcher.h"

namespace ply_slam {

LandmarkFuser::LandmarkFuser(const PinholeCamera& camera, const OrbOptions& orb,
                             const LocalMappingOptions& options)
    : camera_(camera),
      num_levels_(orb.num_levels),
      log_scale_(std::log(orb.scale_factor)),
      chi2_outlier_(options.chi2_outlier),
      radius_px_(options.fuse_radius_px),
      max_distance_(options.fuse_max_descriptor_distance) {}

FusionCounts LandmarkFuser::fuse(Map& map, KeyFrame& keyframe,
                                 const std::vector<KeyFrame*>& neighbours) const {
  FusionCounts changes;
  // Neighbours' landmarks into the new keyframe.
  std::vector<std::shared_ptr<MapPoint>> candidates;
  std::unordered_set<const MapPoint*> seen;
  for (KeyFrame* kf : neighbours)
    for (const auto& p : kf->map_points)
      if (p && !p->bad && seen.insert(p.get()).second) candidates.push_back(p);
  changes += fuseInto(map, keyframe, candidates);

  // The new keyframe's landmarks into each neighbour.
  std::vector<std::shared_ptr<MapPoint>> own;
  for (const auto& p : keyframe.map_points)
    if (p && !p->bad) own.push_back(p);
  for (KeyFrame* kf : neighbours) changes += fuseInto(map, *kf, own);
  return changes;
}

FusionCounts LandmarkFuser::fuseInto(Map& map, KeyFrame& target,
                                     const std::vector<std::shared_ptr<MapPoint>>& points) const {
  const auto& cam = camera_;
  const auto& f = target.features;
  const Eigen::Vector3d centre = target.T_wc().translation();
  const int num_levels = num_levels_;
  FusionCounts changes;
  for (const auto& p : points) {
    if (p->bad || p->seenBy(&target)) continue;
    const Eigen::Vector3d pc = target.T_cw * p->position;
    if (pc.z() <= 0.05) continue;
    const Eigen::Vector2d uv = cam.project(pc);
    if (!cam.inImage(uv)) continue;
    const Eigen::Vector3d ray = p->position - centre;
    const double distance = ray.norm();
    if (distance < 0.8 * p->min_distance || distance > 1.2 * p->max_distance) continue;
    if (ray.dot(p->normal) < 0.5 * distance) continue;
    const int level = p->predictLevel(distance, log_scale_, num_levels);

    int best = std::numeric_limits<int>::max();
    long best_index = -1;
    for (size_t i :
         f.featuresInArea(uv.x(), uv.y(), radius_px_ * (*f.scales)[level], level - 1, level)) {
      // Geometric agreement first: reprojection (and depth where measured) within 95 %.
      const double sigma = f.scale(i);
      double e2 = (f.undistorted[i] - uv).squaredNorm() / (sigma * sigma);
      double chi2 = chi2_outlier_;
      if (f.hasDepth(i)) {
        const double dz = f.depth[i] - pc.z();
        e2 += dz * dz / cam.depth_noise.variance(f.depth[i]);
        chi2 = withDepthDof(chi2);
      }
      if (e2 > chi2) continue;
      const int d = descriptorDistance(p->descriptor, f.descriptors.row(static_cast<int>(i)));
      if (d < best) {
        best = d;
        best_index = static_cast<long>(i);
      }
    }
    if (best_index < 0 || best > max_distance_) continue;

    const auto existing = target.map_points[best_index];
    if (!existing || existing->bad) {
      if (existing) map.removeObservation(target, static_cast<size_t>(best_index));
      map.addObservation(target, static_cast<size_t>(best_index), p);
      ++changes.observations_added;
    } else if (existing != p) {
      // One corner, two landmarks: keep the better established one.
      if (existing->observations() >= p->observations())
        map.replace(p, existing);
      else
        map.replace(existing, p);
      ++changes.landmarks_merged;
    }
  }
  return changes;
}

}  // namespace ply_slam
