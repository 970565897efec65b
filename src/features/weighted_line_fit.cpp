#include "ply_slam/features/weighted_line_fit.h"

#include <Eigen/Eigenvalues>

namespace ply_slam {

bool fitWeightedLine(const std::vector<WeightedPoint2>& points, Eigen::Vector2d& centroid,
                     Eigen::Vector2d& direction) {
  double total = 0.0;
  centroid.setZero();
  for (const auto& e : points) {
    centroid += e.weight * e.p;
    total += e.weight;
  }
  if (total <= 0.0) return false;
  centroid /= total;
  Eigen::Matrix2d scatter = Eigen::Matrix2d::Zero();
  for (const auto& e : points) {
    const Eigen::Vector2d r = e.p - centroid;
    scatter += e.weight * r * r.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> solver(scatter);
  direction = solver.eigenvectors().col(1);  // largest eigenvalue
  return solver.eigenvalues()(1) > 0.0;
}

}  // namespace ply_slam
