#pragma once

#include <Eigen/Geometry>
#include <vector>

namespace ply_slam {

// The rotation nearest to m in the Frobenius norm (SVD; a reflection is never returned).
Eigen::Matrix3d nearestRotation(const Eigen::Matrix3d& m);

// Closed-form rigid alignment (Horn / Umeyama, no scale) minimising sum |gt - T est|^2.
Eigen::Isometry3d alignRigid(const std::vector<Eigen::Vector3d>& est,
                             const std::vector<Eigen::Vector3d>& gt);

// The same with a scale (Umeyama 1991, Sim(3)): gt ~ scale * R est + t. A scale above 1: the
// estimate is smaller than the truth (depth read short, or drift).
struct SimilarityAlignment {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();
  double scale = 1.0;
  Eigen::Vector3d operator()(const Eigen::Vector3d& est) const {
    return scale * (rotation * est) + translation;
  }
};
SimilarityAlignment alignSimilarity(const std::vector<Eigen::Vector3d>& est,
                                    const std::vector<Eigen::Vector3d>& gt);

}  // namespace ply_slam
