// Kept apart from the metrics: the only numerical-linear-algebra piece of the evaluation.
#include "ply_slam/common/rigid_alignment.h"

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

namespace {

// Both sets' means and the rotation that best maps the centred estimate onto the centred
// ground truth: the cross-covariance's SVD (Umeyama 1991; the rotation does not depend on a
// scale).
struct Centred {
  Eigen::Vector3d est_mean = Eigen::Vector3d::Zero(), gt_mean = Eigen::Vector3d::Zero();
  Eigen::Matrix3d rotation;
};

Centred centredRotation(const std::vector<Eigen::Vector3d>& est,
                        const std::vector<Eigen::Vector3d>& gt, const char* who) {
  if (est.size() != gt.size() || est.empty()) {
    throw std::invalid_argument(std::string(who) + ": need equally many (>= 1) points, got " +
                                std::to_string(est.size()) + " estimated and " +
                                std::to_string(gt.size()) + " ground-truth points");
  }
  Centred c;
  const double n = static_cast<double>(est.size());
  for (size_t k = 0; k < est.size(); ++k) {
    c.est_mean += est[k];
    c.gt_mean += gt[k];
  }
  c.est_mean /= n;
  c.gt_mean /= n;
  Eigen::Matrix3d cross = Eigen::Matrix3d::Zero();
  for (size_t k = 0; k < est.size(); ++k)
    cross += (gt[k] - c.gt_mean) * (est[k] - c.est_mean).transpose();
  c.rotation = nearestRotation(cross);
  return c;
}

}  // namespace

Eigen::Isometry3d alignRigid(const std::vector<Eigen::Vector3d>& est,
                             const std::vector<Eigen::Vector3d>& gt) {
  const Centred c = centredRotation(est, gt, "alignRigid");
  Eigen::Isometry3d T_gt_est = Eigen::Isometry3d::Identity();
  T_gt_est.linear() = c.rotation;
  T_gt_est.translation() = c.gt_mean - c.rotation * c.est_mean;
  return T_gt_est;
}

SimilarityAlignment alignSimilarity(const std::vector<Eigen::Vector3d>& est,
                                    const std::vector<Eigen::Vector3d>& gt) {
  const Centred c = centredRotation(est, gt, "alignSimilarity");
  // The least-squares scale once the rotation is fixed: sum g.(R e) / sum |e|^2, centred.
  double along = 0.0, spread = 0.0;
  for (size_t k = 0; k < est.size(); ++k) {
    const Eigen::Vector3d e = c.rotation * (est[k] - c.est_mean);
    along += (gt[k] - c.gt_mean).dot(e);
    spread += e.squaredNorm();
  }
  SimilarityAlignment a;
  a.rotation = c.rotation;
  a.scale = spread > 0.0 ? along / spread : 1.0;  // one point repeated: no size to scale
  a.translation = c.gt_mean - a.scale * (c.rotation * c.est_mean);
  return a;
}

}  // namespace ply_slam
