#include "ply_slam/tracking/pose_optimizer.h"

#include <ceres/ceres.h>
#include <ceres/rotation.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace ply_slam {
namespace {

// Whitened residual of one observation for the pose [angle-axis (3), translation (3)] of T_cw.
// With kDepth the measured depth adds a third, metric residual.
template <bool kDepth>
struct PointCost {
  PointCost(const PointObservation& o, const PinholeCamera& c) : obs(o), cam(c) {}

  template <typename T>
  bool operator()(const T* pose, T* residual) const {
    const T world[3] = {T(obs.world.x()), T(obs.world.y()), T(obs.world.z())};
    T p[3];
    ceres::AngleAxisRotatePoint(pose, world, p);
    p[0] += pose[3];
    p[1] += pose[4];
    p[2] += pose[5];
    if (p[2] <= T(1e-6)) p[2] = T(1e-6);  // behind the camera: large residual, no division by 0
    residual[0] = (T(cam.fx) * p[0] / p[2] + T(cam.cx) - T(obs.pixel.x())) / T(obs.pixel_sigma);
    residual[1] = (T(cam.fy) * p[1] / p[2] + T(cam.cy) - T(obs.pixel.y())) / T(obs.pixel_sigma);
    if constexpr (kDepth) residual[2] = (p[2] - T(obs.depth)) / T(obs.depth_sigma);
    return true;
  }

  const PointObservation obs;
  const PinholeCamera& cam;
};

bool usesDepth(const PointObservation& o) { return o.depth > 0.0 && o.depth_sigma > 0.0; }

}  // namespace

PoseOptimizer::PoseOptimizer(const PinholeCamera& camera, const PoseOptimizerParams& params)
    : camera_(camera), params_(params) {}

double PoseOptimizer::squaredError(const PointObservation& o, const Eigen::Isometry3d& T_cw) const {
  const Eigen::Vector3d p = T_cw * o.world;
  if (p.z() <= 1e-6) return std::numeric_limits<double>::infinity();
  const double e_pixel =
      (camera_.project(p) - o.pixel).squaredNorm() / (o.pixel_sigma * o.pixel_sigma);
  if (!usesDepth(o)) return e_pixel;
  const double e_depth = (p.z() - o.depth) / o.depth_sigma;
  return e_pixel + e_depth * e_depth;
}

int PoseOptimizer::optimize(const std::vector<PointObservation>& observations,
                            Eigen::Isometry3d& T_cw, std::vector<bool>& inlier) const {
  inlier.assign(observations.size(), true);
  if (observations.empty()) return 0;

  double pose[6];
  const Eigen::AngleAxisd aa(T_cw.rotation());
  const Eigen::Vector3d rotation = aa.angle() * aa.axis();
  const Eigen::Vector3d translation = T_cw.translation();
  std::copy(rotation.data(), rotation.data() + 3, pose);
  std::copy(translation.data(), translation.data() + 3, pose + 3);

  auto toIsometry = [&pose]() {
    Eigen::Vector3d w(pose[0], pose[1], pose[2]);
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    const double angle = w.norm();
    if (angle > 1e-12) T.linear() = Eigen::AngleAxisd(angle, w / angle).toRotationMatrix();
    T.translation() = Eigen::Vector3d(pose[3], pose[4], pose[5]);
    return T;
  };

  ceres::Solver::Options options;
  options.linear_solver_type = ceres::DENSE_QR;
  options.max_num_iterations = params_.max_iterations;
  options.logging_type = ceres::SILENT;
  options.num_threads = 1;

  int num_inliers = static_cast<int>(observations.size());
  for (int round = 0; round < params_.rounds; ++round) {
    ceres::Problem::Options problem_options;
    problem_options.cost_function_ownership = ceres::TAKE_OWNERSHIP;
    problem_options.loss_function_ownership = ceres::TAKE_OWNERSHIP;
    ceres::Problem problem(problem_options);
    int used = 0;
    for (size_t i = 0; i < observations.size(); ++i) {
      if (!inlier[i]) continue;
      const auto& o = observations[i];
      if (usesDepth(o)) {
        problem.AddResidualBlock(
            new ceres::AutoDiffCostFunction<PointCost<true>, 3, 6>(new PointCost<true>(o, camera_)),
            new ceres::HuberLoss(std::sqrt(params_.chi2_depth)), pose);
      } else {
        problem.AddResidualBlock(new ceres::AutoDiffCostFunction<PointCost<false>, 2, 6>(
                                     new PointCost<false>(o, camera_)),
                                 new ceres::HuberLoss(std::sqrt(params_.chi2_pixel)), pose);
      }
      ++used;
    }
    if (used < 3) break;
    ceres::Solver::Summary summary;
    ceres::Solve(options, &problem, &summary);

    // Re-classify every observation, so that one wrongly rejected early can come back.
    const Eigen::Isometry3d T = toIsometry();
    num_inliers = 0;
    bool changed = false;
    for (size_t i = 0; i < observations.size(); ++i) {
      const double chi2 = usesDepth(observations[i]) ? params_.chi2_depth : params_.chi2_pixel;
      const bool ok = squaredError(observations[i], T) < chi2;
      changed |= ok != inlier[i];
      inlier[i] = ok;
      num_inliers += ok;
    }
    if (!changed && round > 0) break;
  }
  T_cw = toIsometry();
  return num_inliers;
}

}  // namespace ply_slam
