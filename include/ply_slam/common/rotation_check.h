#pragma once

#include <Eigen/Core>
#include <Eigen/LU>

namespace ply_slam {

// R is a rotation: orthonormal within 1e-6 (relative, Eigen's isApprox) and determinant +1.
inline bool isRotationMatrix(const Eigen::Matrix3d& R) {
  return (R.transpose() * R).isApprox(Eigen::Matrix3d::Identity(), 1e-6) && R.determinant() > 0.0;
}

}  // namespace ply_slam
