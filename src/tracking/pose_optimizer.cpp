#include "ply_slam/tracking/pose_optimizer.h"

#include "ply_slam/common/ceres_solver_options.h"
#include "ply_slam/common/point_residual.h"
#include "ply_slam/common/se3_params.h"
#include "ply_slam/features/line_distance.h"

#include <ceres/ceres.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace ply_slam {
namespace {

PointResidual toResidual(const PointObservation& o) {
  PointResidual r;
  r.u = o.pixel.x();
  r.v = o.pixel.y();
  r.pixel_sigma = o.pixel_sigma;
  r.depth = o.depth;
  r.depth_sigma = o.depth_sigma;
  return r;
}

// The landmark is fixed: only the pose is optimised.
struct FixedPointCost {
  FixedPointCost(const PointObservation& o, const PinholeCamera& c)
      : residual(toResidual(o)), world(o.world), cam(c) {}

  template <typename T>
  bool operator()(const T* pose, T* out) const {
    const T w[3] = {T(world.x()), T(world.y()), T(world.z())};
    residual.evaluate(cam, pose, w, out);
    return true;
  }

  const PointResidual residual;
  const Eigen::Vector3d world;
  const PinholeCamera& cam;
};

// Endpoint-to-line distances of the projected 3D segment (PAPER.md §3), whitened and scaled
// by sqrt(F) so that the squared norm is F e_l' B^-1 e_l.
struct FixedLineCost {
  FixedLineCost(const LineObservation& o, const PinholeCamera& c, double weight)
      : obs(o), cam(c), scale(std::sqrt(weight) / o.pixel_sigma) {}

  template <typename T>
  void endpoint(const T* pose, const Eigen::Vector3d& P, T* out) const {
    const T w[3] = {T(P.x()), T(P.y()), T(P.z())};
    T p[3], uv[2];
    if (!PointResidual::project(cam, pose, w, p, uv)) {
      *out = T(PointResidual::kBehindCameraResidual);
      return;
    }
    *out = lineDistance(obs.line, uv[0], uv[1]) * T(scale);
  }

  template <typename T>
  bool operator()(const T* pose, T* out) const {
    endpoint(pose, obs.start, out);
    endpoint(pose, obs.end, out + 1);
    return true;
  }

  const LineObservation obs;
  const PinholeCamera& cam;
  const double scale;
};

bool usesDepth(const PointObservation& o) { return o.depth > 0.0 && o.depth_sigma > 0.0; }

}  // namespace

double lineBalanceFactor(LineBalance balance, int num_points) {
  return balance == LineBalance::kPaper ? 2.0 * num_points / 50.0 : 1.0;
}

PoseOptimizer::PoseOptimizer(const PinholeCamera& camera, const PoseOptimizerParams& params)
    : camera_(camera), params_(params) {}

double PoseOptimizer::squaredError(const PointObservation& o, const Eigen::Isometry3d& T_cw) const {
  const Eigen::Vector3d p = T_cw * o.world;
  if (!PointResidual::inFront(p)) return std::numeric_limits<double>::infinity();
  const double e_pixel =
      (camera_.project(p) - o.pixel).squaredNorm() / (o.pixel_sigma * o.pixel_sigma);
  if (!usesDepth(o)) return e_pixel;
  const double e_depth = (p.z() - o.depth) / o.depth_sigma;
  return e_pixel + e_depth * e_depth;
}

double PoseOptimizer::squaredLineError(const LineObservation& o,
                                       const Eigen::Isometry3d& T_cw) const {
  const Eigen::Vector3d ps = T_cw * o.start, pe = T_cw * o.end;
  if (!PointResidual::inFront(ps) || !PointResidual::inFront(pe))
    return std::numeric_limits<double>::infinity();
  const double es = lineDistance(o.line, camera_.project(ps));
  const double ee = lineDistance(o.line, camera_.project(pe));
  return (es * es + ee * ee) / (o.pixel_sigma * o.pixel_sigma);
}

int PoseOptimizer::optimize(const std::vector<PointObservation>& observations,
                            Eigen::Isometry3d& T_cw, std::vector<bool>& inlier) const {
  std::vector<bool> line_inlier;
  return optimize(observations, {}, 1.0, T_cw, inlier, line_inlier);
}

int PoseOptimizer::optimize(const std::vector<PointObservation>& observations,
                            const std::vector<LineObservation>& lines, double line_weight,
                            Eigen::Isometry3d& T_cw, std::vector<bool>& inlier,
                            std::vector<bool>& line_inlier) const {
  inlier.assign(observations.size(), true);
  line_inlier.assign(lines.size(), true);
  if (observations.empty() && lines.empty()) return 0;
  // Landmarks behind the camera at the start cannot be reprojected: outliers from the outset.
  for (size_t i = 0; i < observations.size(); ++i)
    inlier[i] = PointResidual::inFront(T_cw * observations[i].world);
  for (size_t k = 0; k < lines.size(); ++k)
    line_inlier[k] = PointResidual::inFront(T_cw * lines[k].start) &&
                     PointResidual::inFront(T_cw * lines[k].end);

  Se3Params pose = toParams(T_cw);

  const ceres::Solver::Options options = toCeres(params_.solver);

  int num_inliers = static_cast<int>(std::count(inlier.begin(), inlier.end(), true));
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
            new ceres::AutoDiffCostFunction<FixedPointCost, 3, 6>(new FixedPointCost(o, camera_)),
            new ceres::HuberLoss(std::sqrt(params_.chi2_depth)), pose.data());
      } else {
        problem.AddResidualBlock(
            new ceres::AutoDiffCostFunction<FixedPointCost, 2, 6>(new FixedPointCost(o, camera_)),
            new ceres::HuberLoss(std::sqrt(params_.chi2_pixel)), pose.data());
      }
      ++used;
    }
    int used_lines = 0;
    for (size_t k = 0; k < lines.size(); ++k) {
      if (!line_inlier[k]) continue;
      problem.AddResidualBlock(new ceres::AutoDiffCostFunction<FixedLineCost, 2, 6>(
                                   new FixedLineCost(lines[k], camera_, line_weight)),
                               new ceres::HuberLoss(std::sqrt(params_.chi2_pixel)), pose.data());
      ++used_lines;
    }
    // Each point or line gives two constraints at least.
    if (used + used_lines < 3) {  // too few to fix six degrees of freedom: nothing fits
      inlier.assign(observations.size(), false);
      line_inlier.assign(lines.size(), false);
      num_inliers = 0;
      break;
    }
    ceres::Solver::Summary summary;
    ceres::Solve(options, &problem, &summary);

    // Re-classify every observation, so that one wrongly rejected early can come back.
    const Eigen::Isometry3d T = fromParams(pose.data());
    num_inliers = 0;
    bool changed = false;
    for (size_t i = 0; i < observations.size(); ++i) {
      const double chi2 = usesDepth(observations[i]) ? params_.chi2_depth : params_.chi2_pixel;
      const bool ok = squaredError(observations[i], T) < chi2;
      changed |= ok != inlier[i];
      inlier[i] = ok;
      num_inliers += ok;
    }
    for (size_t k = 0; k < lines.size(); ++k) {
      const bool ok = squaredLineError(lines[k], T) < params_.chi2_pixel;
      changed |= ok != line_inlier[k];
      line_inlier[k] = ok;
    }
    if (!changed && round > 0) break;
  }
  T_cw = fromParams(pose.data());
  return num_inliers;
}

}  // namespace ply_slam
