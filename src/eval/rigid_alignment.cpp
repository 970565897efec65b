// Kept apart from the metrics: the only numerical-linear-algebra piece of the evaluation.
#include "ply_slam/eval/rigid_alignment.h"

#include <Eigen/SVD>
#include <stdexcept>
#include <string>

namespace ply_slam {

Eigen::Matrix3d nearestRotation(const Eigen::Matrix3d& m) {
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(m, Eigen::ComputeFullU | Eigen::ComputeFullV);
  // Without this sign fix a reflection could win for noisy or planar data.
  Eigen::Vector3d signs(1.0, 1.0, 1.0);
  if ((svd.matrixU() * svd.matrixV().transpose()).determinant() < 0.0) signs.z() = -1.0;
  return svd.matrixU() * signs.asDiagonal() * svd.matrixV().transpose();
}

Eigen::Isometry3d alignRigid(const std::vector<Eigen::Vector3d>& est,
                             const std::vector<Eigen::Vector3d>& gt) {
  if (est.size() != gt.size() || est.empty()) {
    throw std::invalid_argument("alignRigid: need equally many (>= 1) points, got " +
                                std::to_string(est.size()) + " estimated and " +
                                std::to_string(gt.size()) + " ground-truth points");
  }
  const double n = static_cast<double>(est.size());
  Eigen::Vector3d est_mean = Eigen::Vector3d::Zero(), gt_mean = Eigen::Vector3d::Zero();
  for (size_t k = 0; k < est.size(); ++k) {
    est_mean += est[k];
    gt_mean += gt[k];
  }
  est_mean /= n;
  gt_mean /= n;

  // Cross-covariance of the centred point sets; its SVD gives the rotation that best maps the
  // estimate onto the ground truth (Umeyama 1991 without the scale term).
  Eigen::Matrix3d cross = Eigen::Matrix3d::Zero();
  for (size_t k = 0; k < est.size(); ++k) {
    cross += (gt[k] - gt_mean) * (est[k] - est_mean).transpose();
  }
  const Eigen::Matrix3d rotation = nearestRotation(cross);

  Eigen::Isometry3d T_gt_est = Eigen::Isometry3d::Identity();
  T_gt_est.linear() = rotation;
  T_gt_est.translation() = gt_mean - rotation * est_mean;
  return T_gt_est;
}

}  // namespace ply_slam
