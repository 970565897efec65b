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

constexpr int kLocalIterations = 10;  // after each keyframe: the window is small and warm

struct Observation {
  KeyFrame* keyframe;
  size_t index;
  MapPoint* point;
  PointResidual residual;
};

}  // namespace

LocalBundleAdjustmentStats LocalBundleAdjuster::adjust(Map& map, KeyFrame& keyframe) const {
  // Local keyframes: the new one and its best covisible ones.
  std::vector<KeyFrame*> keyframes{&keyframe};
  for (KeyFrame* kf : keyframe.bestCovisible(config_.tracking.local_map_keyframes))
    keyframes.push_back(kf);
  return adjustWindow(map, keyframes, kLocalIterations);
}

LocalBundleAdjustmentStats LocalBundleAdjuster::adjustAll(Map& map, int max_iterations) const {
  std::vector<KeyFrame*> keyframes;
  for (const auto& kf : map.keyFrames()) keyframes.push_back(kf.get());
  return adjustWindow(map, keyframes, max_iterations);
}

LocalBundleAdjustmentStats LocalBundleAdjuster::adjustWindow(
    Map& map, const std::vector<KeyFrame*>& keyframes, int max_iterations) const {
  const auto& t = config_.tracking;
  LocalBundleAdjustmentStats stats;
  // Containers are filled and walked in a fixed order so that the same input gives the same
  // solution.
  std::unordered_set<KeyFrame*> local(keyframes.begin(), keyframes.end());
  std::unordered_map<KeyFrame*, size_t> pose_index;
  std::vector<Se3Params> poses;
  auto addPose = [&](KeyFrame* kf) {
    if (pose_index.emplace(kf, poses.size()).second) poses.push_back(toParams(kf->T_cw));
    return pose_index[kf];
  };
  for (KeyFrame* kf : keyframes) addPose(kf);

  // Their landmarks, and every observation of them (other keyframes enter fixed).
  std::vector<MapPoint*> point_list;
  std::unordered_map<MapPoint*, size_t> point_index;
  std::vector<std::array<double, 3>> points;
  for (KeyFrame* kf : keyframes) {
    for (const auto& p : kf->map_points) {
      if (!p || p->bad || !point_index.emplace(p.get(), points.size()).second) continue;
      point_list.push_back(p.get());
      points.push_back({p->position.x(), p->position.y(), p->position.z()});
    }
  }
  std::vector<Observation> observations;
  for (MapPoint* point : point_list) {
    for (const auto& [kf, i] : point->observers) {
      addPose(kf);
      const auto& f = kf->features;
      PointResidual r;
      r.u = f.undistorted[i].x();
      r.v = f.undistorted[i].y();
      r.pixel_sigma = f.scale(i);
      if (f.hasDepth(i)) {
        r.depth = f.depth[i];
        r.depth_sigma = std::sqrt(config_.camera.depth_noise.varianceAgainstMap(r.depth));
      }
      observations.push_back({kf, i, point, r});
    }
  }

  ceres::Problem::Options problem_options;
  ceres::Problem problem(problem_options);
  for (auto& o : observations) {
    // Behind the keyframe already: no constraint, and removed as an outlier below.
    if ((o.keyframe->T_cw * o.point->position).z() <= PointResidual::kMinDepth) continue;
    const int dims = o.residual.hasDepth() ? 3 : 2;
    ceres::CostFunction* cost = dims == 3
                                    ? static_cast<ceres::CostFunction*>(
                                          new ceres::AutoDiffCostFunction<ObservationCost, 3, 6, 3>(
                                              new ObservationCost(o.residual, config_.camera)))
                                    : new ceres::AutoDiffCostFunction<ObservationCost, 2, 6, 3>(
                                          new ObservationCost(o.residual, config_.camera));
    const double chi2 = dims == 3 ? t.chi2_outlier + 1.824 : t.chi2_outlier;
    problem.AddResidualBlock(cost, new ceres::HuberLoss(std::sqrt(chi2)),
                             poses[pose_index[o.keyframe]].data(),
                             points[point_index[o.point]].data());
  }
  // Fixed: keyframes outside the local window, and the first keyframe (gauge freedom).
  for (const auto& [kf, index] : pose_index) {
    if (local.count(kf) && kf->id != 0) {
      ++stats.keyframes;
    } else {
      ++stats.fixed_keyframes;
      double* pose = poses[index].data();
      if (problem.HasParameterBlock(pose)) problem.SetParameterBlockConstant(pose);
    }
  }
  stats.points = static_cast<int>(points.size());
  stats.observations = static_cast<int>(observations.size());

  ceres::Solver::Options options;
  options.linear_solver_type = ceres::SPARSE_SCHUR;
  options.max_num_iterations = max_iterations;
  options.logging_type = ceres::SILENT;
  options.num_threads = 1;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);

  // Drop observations that are still outliers; write back poses and landmarks.
  for (auto& o : observations) {
    double r[3] = {0.0, 0.0, 0.0};
    const auto& pose = poses[pose_index[o.keyframe]];
    const auto& position = points[point_index[o.point]];
    o.residual.evaluate(config_.camera, pose.data(), position.data(), r);
    const bool depth = o.residual.hasDepth();
    const double e2 = r[0] * r[0] + r[1] * r[1] + (depth ? r[2] * r[2] : 0.0);
    if (e2 > (depth ? t.chi2_outlier + 1.824 : t.chi2_outlier)) {
      map.removeObservation(*o.keyframe, o.index);
      ++stats.outliers_removed;
    }
  }
  for (const auto& [kf, index] : pose_index)
    if (local.count(kf)) kf->T_cw = fromParams(poses[index].data());
  for (size_t k = 0; k < point_list.size(); ++k) {
    point_list[k]->position = Eigen::Vector3d(points[k][0], points[k][1], points[k][2]);
    if (point_list[k]->observers.empty()) point_list[k]->bad = true;
  }
  return stats;
}

}  // namespace ply_slam
