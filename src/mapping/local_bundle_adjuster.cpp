#include "ply_slam/mapping/local_bundle_adjuster.h"

#include <ceres/ceres.h>

#include <algorithm>
#include <unordered_map>
#include <unordered_set>

#include "ply_slam/common/point_residual.h"
#include "ply_slam/common/se3_params.h"

namespace ply_slam {
namespace {

struct ObservationCost {
  ObservationCost(const PointResidual& r, const PinholeCamera& c) : residual(r), cam(c) {}
  template <typename T>
  bool operator()(const T* pose, const T* point, T* out) const {
    residual.evaluate(cam, pose, point, out);
    return true;
  }
  const PointResidual residual;
  const PinholeCamera& cam;
};

struct Observation {
  KeyFrame* keyframe;
  size_t index;
  MapPoint* point;
  PointResidual residual;
};

}  // namespace

LocalBundleAdjustmentStats LocalBundleAdjuster::adjust(Map& map, KeyFrame& keyframe) const {
  const auto& t = config_.tracking;
  LocalBundleAdjustmentStats stats;

  // Local keyframes: the new one and its best covisible ones.
  std::vector<std::pair<int, KeyFrame*>> neighbours;
  for (const auto& [kf, weight] : keyframe.covisibility) neighbours.emplace_back(weight, kf);
  std::sort(neighbours.begin(), neighbours.end(),
            [](const auto& a, const auto& b) { return a.first > b.first; });
  std::unordered_set<KeyFrame*> local{&keyframe};
  for (const auto& [weight, kf] : neighbours) {
    if (static_cast<int>(local.size()) > t.local_map_keyframes) break;
    local.insert(kf);
  }
  std::unordered_map<KeyFrame*, Se3Params> poses;
  for (KeyFrame* kf : local) poses[kf] = toParams(kf->T_cw);

  // Their landmarks, and every observation of them (other keyframes enter fixed).
  std::unordered_map<MapPoint*, std::array<double, 3>> points;
  std::vector<Observation> observations;
  for (const auto& [kf, pose] : poses) {
    for (const auto& p : kf->map_points) {
      if (!p || p->bad || points.count(p.get())) continue;
      points[p.get()] = {p->position.x(), p->position.y(), p->position.z()};
    }
  }
  for (auto& [point, position] : points) {
    for (const auto& [kf, i] : point->observers) {
      if (!poses.count(kf)) poses[kf] = toParams(kf->T_cw);
      const auto& f = kf->features;
      PointResidual r;
      r.u = f.undistorted[i].x();
      r.v = f.undistorted[i].y();
      r.pixel_sigma = f.scale(i);
      if (f.hasDepth(i)) {
        r.depth = f.depth[i];
        r.depth_sigma = std::sqrt(config_.camera.depth_noise.variance(r.depth));
      }
      observations.push_back({kf, i, point, r});
    }
  }

  ceres::Problem::Options problem_options;
  ceres::Problem problem(problem_options);
  for (auto& o : observations) {
    const int dims = o.residual.hasDepth() ? 3 : 2;
    ceres::CostFunction* cost = dims == 3
                                    ? static_cast<ceres::CostFunction*>(
                                          new ceres::AutoDiffCostFunction<ObservationCost, 3, 6, 3>(
                                              new ObservationCost(o.residual, config_.camera)))
                                    : new ceres::AutoDiffCostFunction<ObservationCost, 2, 6, 3>(
                                          new ObservationCost(o.residual, config_.camera));
    const double chi2 = dims == 3 ? t.chi2_outlier + 1.824 : t.chi2_outlier;
    problem.AddResidualBlock(cost, new ceres::HuberLoss(std::sqrt(chi2)), poses[o.keyframe].data(),
                             points[o.point].data());
  }
  // Fixed: keyframes outside the local window, and the first keyframe (gauge freedom).
  for (auto& [kf, pose] : poses) {
    if (local.count(kf) && kf->id != 0) {
      ++stats.keyframes;
    } else {
      ++stats.fixed_keyframes;
      if (problem.HasParameterBlock(pose.data())) problem.SetParameterBlockConstant(pose.data());
    }
  }
  stats.points = static_cast<int>(points.size());
  stats.observations = static_cast<int>(observations.size());

  ceres::Solver::Options options;
  options.linear_solver_type = ceres::SPARSE_SCHUR;
  options.max_num_iterations = 10;
  options.logging_type = ceres::SILENT;
  options.num_threads = 1;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);

  // Drop observations that are still outliers; write back poses and landmarks.
  for (auto& o : observations) {
    double r[3];
    const auto& pose = poses[o.keyframe];
    const auto& position = points[o.point];
    o.residual.evaluate(config_.camera, pose.data(), position.data(), r);
    const bool depth = o.residual.hasDepth();
    const double e2 = r[0] * r[0] + r[1] * r[1] + (depth ? r[2] * r[2] : 0.0);
    if (e2 > (depth ? t.chi2_outlier + 1.824 : t.chi2_outlier)) {
      map.removeObservation(*o.keyframe, o.index);
      ++stats.outliers_removed;
    }
  }
  for (auto& [kf, pose] : poses) kf->T_cw = fromParams(pose.data());
  for (auto& [point, position] : points) {
    point->position = Eigen::Vector3d(position[0], position[1], position[2]);
    if (point->observers.empty()) point->bad = true;
  }
  return stats;
}

}  // namespace ply_slam
