#include "ply_slam/eval/loop_ground_truth.h"

#include <algorithm>
#include <cmath>

#include "ply_slam/eval/trajectory_metrics.h"

namespace ply_slam {
namespace {

bool onMover(const cv::Mat& movers, int u, int v) {
  return !movers.empty() && movers.at<uint8_t>(v, u) != 0;
}

}  // namespace

double viewOverlap(const GroundTruthView& a, const GroundTruthView& b, const PinholeCamera& camera,
                   const LoopGroundTruthParams& params) {
  const Eigen::Isometry3d T_ba = b.T_wc.inverse() * a.T_wc;
  long valid = 0, seen = 0;
  for (int v = 0; v < a.depth.rows; v += params.pixel_step)
    for (int u = 0; u < a.depth.cols; u += params.pixel_step) {
      const float z = a.depth.at<float>(v, u);
      if (!(z > 0.f) || onMover(a.movers, u, v)) continue;
      const Eigen::Vector3d p_b = T_ba * camera.backProject(Eigen::Vector2d(u, v), z);
      const Eigen::Vector2d uv = camera.project(p_b);
      const bool in_view = p_b.z() > 0.0 && camera.inImage(uv);
      const int u_b = static_cast<int>(uv.x()), v_b = static_cast<int>(uv.y());
      if (in_view && onMover(b.movers, u_b, v_b)) continue;
      ++valid;
      if (!in_view) continue;
      const float z_b = b.depth.at<float>(v_b, u_b);
      const double tolerance =
          std::max(params.depth_tolerance_m, params.depth_tolerance_ratio * p_b.z());
      seen += z_b > 0.f && std::abs(z_b - p_b.z()) < tolerance;
    }
  return valid > 0 ? static_cast<double>(seen) / valid : 0.0;
}

LoopTruth loopTruth(const GroundTruthView& a, const GroundTruthView& b, const PinholeCamera& camera,
                    const LoopGroundTruthParams& params) {
  if (std::abs(a.stamp - b.stamp) <= params.min_gap_s) return LoopTruth::kFalse;
  const Eigen::Isometry3d T_ab = a.T_wc.inverse() * b.T_wc;
  const double distance = T_ab.translation().norm();
  const double angle = rotationAngleDeg(T_ab.linear());
  if (distance > params.false_distance_m || angle > params.false_angle_deg)
    return LoopTruth::kFalse;
  if (std::max(viewOverlap(a, b, camera, params), viewOverlap(b, a, camera, params)) <
      params.min_overlap)
    return LoopTruth::kFalse;
  return distance <= params.max_distance_m && angle <= params.max_angle_deg ? LoopTruth::kTrue
                                                                            : LoopTruth::kDontCare;
}

}  // namespace ply_slam
