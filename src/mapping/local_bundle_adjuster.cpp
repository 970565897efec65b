#include "ply_slam/mapping/local_bundle_adjuster.h"

#include <ceres/ceres.h>

#include <algorithm>
#include <optional>
#include <unordered_map>

#include "ply_slam/common/ceres_solver_options.h"
#include "ply_slam/common/chi_square.h"

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

// Stops the solver after the iteration during which `abandon` turned true.
class AbandonCallback : public ceres::IterationCallback {
 public:
  explicit AbandonCallback(const std::atomic<bool>& abandon) : abandon_(abandon) {}
  ceres::CallbackReturnType operator()(const ceres::IterationSummary&) override {
    return abandon_ ? ceres::SOLVER_ABORT : ceres::SOLVER_CONTINUE;
  }

 private:
  const std::atomic<bool>& abandon_;
};

}  // namespace

LocalBundleAdjustmentStats LocalBundleAdjuster::adjust(Map& map, KeyFrame& keyframe) const {
  BundleWindow window = gatherLocal(keyframe);
  solve(window);
  return apply(map, window);
}

BundleWindow LocalBundleAdjuster::gatherLocal(KeyFrame& keyframe) const {
  std::vector<KeyFrame*> keyframes{&keyframe};
  for (KeyFrame* kf : keyframe.bestCovisible(options_.window_keyframes)) keyframes.push_back(kf);
  return gather(keyframes, options_.bundle_solver.max_iterations, true, {});
}

BundleWindow LocalBundleAdjuster::gatherAll(const Map& map, int max_iterations,
                                            const std::function<void()>& between) const {
  const auto all = map.keyFrames();
  std::vector<KeyFrame*> keyframes;
  for (const auto& kf : all) keyframes.push_back(kf.get());
  // Every keyframe of now is in: an outsider was made while `between` had let go of the lock.
  BundleWindow window = gather(keyframes, max_iterations, false, between);
  window.keyframes = all;
  return window;
}

BundleWindow LocalBundleAdjuster::gather(const std::vector<KeyFrame*>& keyframes,
                                         int max_iterations, bool outsiders_fixed,
                                         const std::function<void()>& between) const {
  // Filled in a fixed order so that the same map gives the same solution.
  BundleWindow window;
  window.max_iterations = max_iterations;
  std::unordered_map<const KeyFrame*, size_t> pose_index;
  auto addPose = [&](KeyFrame* kf, bool local) -> std::optional<size_t> {
    const auto it = pose_index.find(kf);
    if (it != pose_index.end()) return it->second;
    if (!local && !outsiders_fixed) return std::nullopt;
    pose_index.emplace(kf, window.poses.size());
    window.poses.push_back({kf, toParams(kf->T_cw), local, !local || kf->id == 0});
    return window.poses.size() - 1;
  };
  for (KeyFrame* kf : keyframes) addPose(kf, true);

  // Their landmarks, and every observation of them.
  std::unordered_map<const MapPoint*, size_t> point_index;
  for (KeyFrame* kf : keyframes) {
    for (const auto& p : kf->map_points) {
      if (!p || p->bad || !point_index.emplace(p.get(), window.points.size()).second) continue;
      window.landmarks.push_back(p);
      window.points.push_back({p->position.x(), p->position.y(), p->position.z()});
    }
    if (between) between();
  }
  for (size_t k = 0; k < window.landmarks.size(); ++k) {
    const MapPoint& point = *window.landmarks[k];
    for (const auto& [kf, i] : point.observers) {
      const std::optional<size_t> pose = addPose(kf, false);
      if (!pose) continue;
      BundleWindow::Observation o;
      o.pose = *pose;
      o.point = k;
      o.index = i;
      const auto& f = kf->features;
      o.residual.u = f.undistorted[i].x();
      o.residual.v = f.undistorted[i].y();
      o.residual.pixel_sigma = f.scale(i);
      if (f.hasDepth(i)) {
        o.residual.depth = f.depth[i];
        o.residual.depth_sigma = std::sqrt(camera_.depth_noise.varianceAgainstMap(f.depth[i]));
      }
      o.behind = !PointResidual::inFront(kf->T_cw * point.position);
      window.observations.push_back(o);
    }
    if (between) between();
  }
  return window;
}

double LocalBundleAdjuster::chi2Bound(const PointResidual& residual) const {
  const double chi2 = options_.chi2_outlier;
  return residual.hasDepth() ? withDepthDof(chi2) : chi2;
}

bool LocalBundleAdjuster::solve(BundleWindow& window, const std::atomic<bool>* abandon) const {
  ceres::Problem problem;
  for (auto& o : window.observations) {
    if (o.behind) continue;  // removed as an outlier in apply
    ceres::CostFunction* cost = o.residual.hasDepth()
                                    ? static_cast<ceres::CostFunction*>(
                                          new ceres::AutoDiffCostFunction<ObservationCost, 3, 6, 3>(
                                              new ObservationCost(o.residual, camera_)))
                                    : new ceres::AutoDiffCostFunction<ObservationCost, 2, 6, 3>(
                                          new ObservationCost(o.residual, camera_));
    problem.AddResidualBlock(cost, new ceres::HuberLoss(std::sqrt(chi2Bound(o.residual))),
                             window.poses[o.pose].params.data(), window.points[o.point].data());
  }
  for (auto& pose : window.poses)
    if (pose.fixed && problem.HasParameterBlock(pose.params.data()))
      problem.SetParameterBlockConstant(pose.params.data());

  ceres::Solver::Options options = toCeres(options_.bundle_solver);
  options.max_num_iterations = window.max_iterations;  // local or global (gatherAll)
  std::optional<AbandonCallback> abandoned;
  if (abandon) options.callbacks.push_back(&abandoned.emplace(*abandon));
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  return summary.termination_type != ceres::USER_FAILURE;
}

LocalBundleAdjustmentStats LocalBundleAdjuster::apply(Map& map, const BundleWindow& window) const {
  LocalBundleAdjustmentStats stats;
  for (const auto& pose : window.poses) ++(pose.fixed ? stats.fixed_keyframes : stats.keyframes);
  stats.points = static_cast<int>(window.points.size());
  stats.observations = static_cast<int>(window.observations.size());
  // Observations that are still outliers leave the map, if still linked as they were.
  for (const auto& o : window.observations) {
    double r[3] = {0.0, 0.0, 0.0};
    o.residual.evaluate(camera_, window.poses[o.pose].params.data(), window.points[o.point].data(),
                        r);
    const double e2 = r[0] * r[0] + r[1] * r[1] + (o.residual.hasDepth() ? r[2] * r[2] : 0.0);
    if (!(e2 > chi2Bound(o.residual))) continue;
    KeyFrame& kf = *window.poses[o.pose].keyframe;
    if (kf.bad || kf.map_points[o.index] != window.landmarks[o.point]) continue;
    map.removeObservation(kf, o.index);
    ++stats.outliers_removed;
  }
  for (const auto& pose : window.poses)
    if (pose.local && !pose.keyframe->bad) pose.keyframe->T_cw = fromParams(pose.params.data());
  for (size_t k = 0; k < window.landmarks.size(); ++k) {
    MapPoint& point = *window.landmarks[k];
    if (point.bad) continue;  // merged or culled meanwhile
    point.position = Eigen::Vector3d(window.points[k][0], window.points[k][1], window.points[k][2]);
    if (point.observers.empty()) map.erasePoint(window.landmarks[k]);  // nobody sees it now
  }
  return stats;
}

}  // namespace ply_slam
