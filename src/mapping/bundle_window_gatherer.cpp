#include "ply_slam/mapping/bundle_window_gatherer.h"

#include <cmath>

namespace ply_slam {
namespace {

constexpr size_t kNoPose = static_cast<size_t>(-1);

}  // namespace

BundleWindowGatherer::BundleWindowGatherer(const PinholeCamera& camera, int max_iterations,
                                           bool fixed_observers)
    : camera_(camera), fixed_observers_(fixed_observers) {
  window_.max_iterations = max_iterations;
}

size_t BundleWindowGatherer::addPose(KeyFrame* keyframe, bool in_window) {
  const auto it = pose_index_.find(keyframe);
  if (it != pose_index_.end()) return it->second;
  if (!in_window && !fixed_observers_) return kNoPose;
  pose_index_.emplace(keyframe, window_.poses.size());
  window_.poses.push_back(
      {keyframe, toParams(keyframe->T_cw), in_window, !in_window || keyframe->id == 0});
  return window_.poses.size() - 1;
}

void BundleWindowGatherer::addLandmarksOf(const KeyFrame& keyframe) {
  for (const auto& p : keyframe.map_points) {
    if (!p || p->bad || !point_index_.emplace(p.get(), window_.points.size()).second) continue;
    window_.landmarks.push_back(p);
    window_.points.push_back({p->position.x(), p->position.y(), p->position.z()});
  }
}

size_t BundleWindowGatherer::addObservationsOf(size_t k) {
  const MapPoint& point = *window_.landmarks[k];
  size_t added = 0;
  for (const auto& [kf, i] : point.observers) {
    BundleWindow::Observation o;
    o.pose = addPose(kf, false);
    if (o.pose == kNoPose) continue;
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
    window_.observations.push_back(o);
    ++added;
  }
  return added;
}

}  // namespace ply_slam
