#include "ply_slam/mapping/local_bundle_adjuster.h"

#include <ceres/ceres.h>

#include <algorithm>
#include <optional>

#include "ply_slam/common/ceres_solver_options.h"
#include "ply_slam/common/chi_square.h"
#include "ply_slam/mapping/bundle_window_gatherer.h"

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
  return gather(keyframes, options_.bundle_solver.max_iterations);
}

BundleWindow LocalBundleAdjuster::gatherAll(const Map& map, int max_iterations,
                                            const std::function<void()>& between) const {
  const auto all = map.keyFrames();
  // The window's keyframes are those of now: keyframes the tracker makes while `between` has
  // let go of the lock see some of its landmarks, but stay out.
  BundleWindowGatherer gatherer(camera_, max_iterations, false);
  for (const auto& kf : all) gatherer.addKeyFrame(kf.get());
  for (const auto& kf : all) {
    gatherer.addLandmarksOf(*kf);
    if (between) between();
  }
  for (size_t k = 0; k < gatherer.landmarks(); ++k) {
    gatherer.addObservationsOf(k);
    if (between) between();
  }
  BundleWindow window = gatherer.take();
  window.keyframes = all;
  return window;
}

BundleWindow LocalBundleAdjuster::gather(const std::vector<KeyFrame*>& keyframes,
                                         int max_iterations) const {
  BundleWindowGatherer gatherer(camera_, max_iterations, true);
  for (KeyFrame* kf : keyframes) gatherer.addKeyFrame(kf);
  for (KeyFrame* kf : keyframes) gatherer.addLandmarksOf(*kf);
  for (size_t k = 0; k < gatherer.landmarks(); ++k) gatherer.addObservationsOf(k);
  return gatherer.take();
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
    if (point.observers.empty()) point.bad = true;
  }
  return stats;
}

}  // namespace ply_slam
