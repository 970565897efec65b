#pragma once

#include <ceres/autodiff_cost_function.h>
#include <ceres/rotation.h>

#include <Eigen/Geometry>
#include <cmath>

namespace ply_slam {

// The logarithm of a rigid transform (q, t): [omega, rho], omega the rotation's angle-axis and
// rho = V(omega)^-1 t, so that exp([omega, rho]) = (q, t). Templated for Ceres' Jets.
template <typename T>
Eigen::Matrix<T, 6, 1> se3Log(const Eigen::Quaternion<T>& q, const Eigen::Matrix<T, 3, 1>& t) {
  using std::sqrt;
  using std::tan;
  // Below this squared angle (0.01 rad) the series of c is exact to ~1e-13 and the closed form
  // would divide two vanishing numbers.
  constexpr double kSeriesBelowSquaredAngle = 1e-4;
  const T wxyz[4] = {q.w(), q.x(), q.y(), q.z()};
  Eigen::Matrix<T, 3, 1> omega;
  ceres::QuaternionToAngleAxis(wxyz, omega.data());
  // V^-1 = I - W/2 + c W^2 with W = [omega]x and c = (1 - (theta/2) cot(theta/2)) / theta^2.
  const T theta_sq = omega.squaredNorm();
  T c;
  if (theta_sq < T(kSeriesBelowSquaredAngle)) {
    c = T(1.0 / 12.0) + theta_sq / T(720.0);
  } else {
    const T half = sqrt(theta_sq) / T(2.0);
    c = (T(1.0) - half / tan(half)) / theta_sq;
  }
  const Eigen::Matrix<T, 3, 1> w_t = omega.cross(t);
  Eigen::Matrix<T, 6, 1> log;
  log.template head<3>() = omega;
  log.template tail<3>() = t - T(0.5) * w_t + c * omega.cross(w_t);
  return log;
}

// One edge of the pose graph: how far the estimated relative pose of two keyframes a, b
// (T_ab = T_wa^-1 T_wb) is from the measured one. The residual is the SE(3) logarithm of
// E = T_ab_measured^-1 T_ab, [rotation (rad), translation (m)], each part divided by its sigma
// and multiplied by sqrt(weight). Parameters: a's rotation as an Eigen quaternion (x, y, z, w)
// and translation, then b's (camera -> world).
class RelativePoseCost {
 public:
  RelativePoseCost(const Eigen::Isometry3d& T_ab_measured, double rotation_scale,
                   double translation_scale)
      : q_inverse_(Eigen::Quaterniond(T_ab_measured.rotation()).conjugate()),
        t_(T_ab_measured.translation()),
        rotation_scale_(rotation_scale),
        translation_scale_(translation_scale) {}

  // The scales are sqrt(weight) / sigma; Ceres takes ownership of the returned cost.
  static ceres::CostFunction* create(const Eigen::Isometry3d& T_ab_measured, double rotation_scale,
                                     double translation_scale) {
    return new ceres::AutoDiffCostFunction<RelativePoseCost, 6, 4, 3, 4, 3>(
        new RelativePoseCost(T_ab_measured, rotation_scale, translation_scale));
  }

  template <typename T>
  bool operator()(const T* q_a, const T* t_a, const T* q_b, const T* t_b, T* residual) const {
    using Quaternion = Eigen::Quaternion<T>;
    using Vector3 = Eigen::Matrix<T, 3, 1>;
    const Eigen::Map<const Quaternion> qa(q_a), qb(q_b);
    const Eigen::Map<const Vector3> ta(t_a), tb(t_b);
    // Unit quaternions (the manifold keeps them so): the conjugate is the inverse.
    const Quaternion qa_inverse = qa.conjugate();
    const Quaternion q_measured_inverse = q_inverse_.template cast<T>();
    const Quaternion q_error = q_measured_inverse * (qa_inverse * qb);
    const Vector3 t_error = q_measured_inverse * (qa_inverse * (tb - ta) - t_.template cast<T>());
    const Eigen::Matrix<T, 6, 1> log = se3Log(q_error, t_error);
    for (int i = 0; i < 3; ++i) {
      residual[i] = T(rotation_scale_) * log[i];
      residual[i + 3] = T(translation_scale_) * log[i + 3];
    }
    return true;
  }

 private:
  const Eigen::Quaterniond q_inverse_;  // measured rotation, inverted
  const Eigen::Vector3d t_;             // measured translation
  const double rotation_scale_;
  const double translation_scale_;
};

}  // namespace ply_slam
