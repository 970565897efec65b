#include "ply_slam/loop/geometric_check.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <utility>

#include "ply_slam/common/angles.h"
#include "ply_slam/common/rigid_alignment.h"

namespace ply_slam {
namespace {

using Indices = std::vector<size_t>;

// Three distinct indices, or none when they repeat or are (nearly) collinear (a rotation
// about their line would be undetermined).
Indices sampleTriple(const std::vector<PutativeMatch>& matches, std::mt19937& rng) {
  std::uniform_int_distribution<size_t> pick(0, matches.size() - 1);
  Indices s = {pick(rng), pick(rng), pick(rng)};
  if (s[0] == s[1] || s[0] == s[2] || s[1] == s[2]) return {};
  const Eigen::Vector3d& a = matches[s[0]].p_candidate;
  const double twice_area =
      (matches[s[1]].p_candidate - a).cross(matches[s[2]].p_candidate - a).norm();
  if (twice_area < 1e-4) return {};  // m^2: e.g. 1 cm off a 1 m line
  return s;
}

Eigen::Isometry3d fit(const std::vector<PutativeMatch>& matches, const Indices& subset) {
  std::vector<Eigen::Vector3d> candidate, query;
  for (size_t k : subset) {
    candidate.push_back(matches[k].p_candidate);
    query.push_back(matches[k].p_query);
  }
  return alignRigid(candidate, query);  // T_query_candidate
}

Indices inliersOf(const Eigen::Isometry3d& T, const std::vector<PutativeMatch>& matches,
                  const std::vector<double>& bounds) {
  Indices inliers;
  for (size_t k = 0; k < matches.size(); ++k) {
    if ((matches[k].p_query - T * matches[k].p_candidate).norm() < bounds[k]) inliers.push_back(k);
  }
  return inliers;
}

// Most 3D inliers over options.ransac_iterations minimal samples (ties: the first found).
Indices bestConsensus(const std::vector<PutativeMatch>& matches, const std::vector<double>& bounds,
                      const LoopOptions& options) {
  std::mt19937 rng(options.ransac_seed);
  Indices best;
  for (int it = 0; it < options.ransac_iterations; ++it) {
    const Indices sample = sampleTriple(matches, rng);
    if (sample.empty()) continue;
    Indices inliers = inliersOf(fit(matches, sample), matches, bounds);
    if (inliers.size() > best.size()) best = std::move(inliers);
  }
  return best;
}

// Least squares on the inliers, then the inliers of that pose, until they stop changing.
Eigen::Isometry3d refine(const std::vector<PutativeMatch>& matches,
                         const std::vector<double>& bounds, const LoopOptions& options,
                         Indices& inliers) {
  Eigen::Isometry3d T = fit(matches, inliers);
  for (int r = 0; r < options.refine_iterations; ++r) {
    Indices next = inliersOf(T, matches, bounds);
    if (next == inliers || next.size() < 3) break;
    inliers = std::move(next);
    T = fit(matches, inliers);
  }
  return T;
}

bool reprojects(const Eigen::Vector3d& p, const Eigen::Vector2d& uv, const PinholeCamera& camera,
                double max_px) {
  return p.z() > 0.0 && (camera.project(p) - uv).norm() < max_px;
}

// The motion is small enough for the two cameras to stand at one place.
bool isRevisit(const Eigen::Isometry3d& T, const LoopOptions& options) {
  return T.translation().norm() <= options.max_revisit_distance_m &&
         rotationAngleDeg(T.linear()) <= options.max_revisit_angle_deg;
}

}  // namespace

double inlierDistance(double z_q, double z_c, const LoopOptions& options) {
  const double sigma =
      std::sqrt(options.depth_noise.variance(z_q) + options.depth_noise.variance(z_c));
  return std::max(options.min_inlier_distance, options.inlier_sigma_factor * sigma);
}

GeometricCheckResult checkLoopGeometry(const std::vector<PutativeMatch>& matches,
                                       const PinholeCamera& camera, const LoopOptions& options) {
  GeometricCheckResult result;
  if (matches.size() < 3) return result;
  std::vector<double> bounds;  // the depth-aware 3D bound does not depend on the pose
  for (const PutativeMatch& m : matches) {
    bounds.push_back(inlierDistance(m.p_query.z(), m.p_candidate.z(), options));
  }
  Indices inliers = bestConsensus(matches, bounds, options);
  if (inliers.size() < 3) return result;
  const Eigen::Isometry3d T = refine(matches, bounds, options, inliers);
  result.T_query_candidate = T;
  result.inliers_3d = static_cast<int>(inliers.size());

  const Eigen::Isometry3d T_inv = T.inverse();
  std::vector<bool> is_3d_inlier(matches.size(), false);
  for (size_t k : inliers) is_3d_inlier[k] = true;
  for (size_t k = 0; k < matches.size(); ++k) {
    const PutativeMatch& m = matches[k];
    if (!reprojects(T * m.p_candidate, m.uv_query, camera, options.reprojection_px) ||
        !reprojects(T_inv * m.p_query, m.uv_candidate, camera, options.reprojection_px)) {
      continue;
    }
    ++result.reprojection_inliers;
    if (is_3d_inlier[k]) result.inliers.push_back(k);
  }
  result.accepted = result.inliers_3d >= options.min_inliers_3d &&
                    result.reprojection_inliers >= options.min_reprojection_inliers &&
                    isRevisit(T, options);
  return result;
}

}  // namespace ply_slam
