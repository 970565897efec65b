#include "ply_slam/eval/pose_interpolation.h"

#include <algorithm>
#include <cmath>

namespace ply_slam {

std::optional<Eigen::Isometry3d> interpolatePose(const Trajectory& trajectory, double stamp,
                                                 double max_gap) {
  const auto after = std::lower_bound(trajectory.begin(), trajectory.end(), stamp,
                                      [](const StampedPose& p, double t) { return p.stamp < t; });
  if (after == trajectory.end() || after == trajectory.begin()) {
    if (after != trajectory.end() && std::abs(after->stamp - stamp) < 1e-6) return after->T_wc;
    return std::nullopt;
  }
  const StampedPose& b = *after;
  const StampedPose& a = *(after - 1);
  if (b.stamp - a.stamp > max_gap) return std::nullopt;
  const double s = (stamp - a.stamp) / (b.stamp - a.stamp);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::Quaterniond(a.T_wc.linear())
                   .slerp(s, Eigen::Quaterniond(b.T_wc.linear()))
                   .toRotationMatrix();
  T.translation() = (1.0 - s) * a.T_wc.translation() + s * b.T_wc.translation();
  return T;
}

}  // namespace ply_slam
