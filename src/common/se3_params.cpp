#include "ply_slam/common/se3_params.h"

namespace ply_slam {

Se3Params toParams(const Eigen::Isometry3d& T) {
  const Eigen::AngleAxisd aa(T.rotation());
  const Eigen::Vector3d w = aa.angle() * aa.axis();
  const Eigen::Vector3d t = T.translation();
  return {w.x(), w.y(), w.z(), t.x(), t.y(), t.z()};
}

Eigen::Isometry3d fromParams(const double* params) {
  const Eigen::Vector3d w(params[0], params[1], params[2]);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  const double angle = w.norm();
  if (angle > 1e-12) T.linear() = Eigen::AngleAxisd(angle, w / angle).toRotationMatrix();
  T.translation() = Eigen::Vector3d(params[3], params[4], params[5]);
  return T;
}

Eigen::Isometry3d nearestRigid(const Eigen::Isometry3d& T) {
  Eigen::Isometry3d out = T;
  out.linear() = Eigen::Quaterniond(T.linear()).normalized().toRotationMatrix();
  return out;
}

}  // namespace ply_slam
