#pragma once

#include <Eigen/Geometry>

namespace ply_slam {

// Velocity of the camera pose T_cw: a point fixed in the world moves in camera coordinates
// as P(t + dt) = exp([angular] dt) P(t) + linear dt (for small dt).
struct CameraVelocity {
  Eigen::Vector3d angular = Eigen::Vector3d::Zero();  // rad/s, camera frame
  Eigen::Vector3d linear = Eigen::Vector3d::Zero();   // m/s, camera frame

  // The constant velocity that moves the camera from pose T_cw_from to T_cw_to in dt seconds.
  static CameraVelocity between(const Eigen::Isometry3d& T_cw_from,
                                const Eigen::Isometry3d& T_cw_to, double dt) {
    const Eigen::Isometry3d step = T_cw_to * T_cw_from.inverse();
    const Eigen::AngleAxisd rotation(step.rotation());
    return {rotation.angle() * rotation.axis() / dt, step.translation() / dt};
  }

  // T_{c(t+dt) c(t)}: camera coordinates at t to those at t + dt.
  Eigen::Isometry3d over(double dt) const {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    const Eigen::Vector3d w = angular * dt;
    if (w.norm() > 1e-12)
      T.linear() = Eigen::AngleAxisd(w.norm(), w.normalized()).toRotationMatrix();
    T.translation() = linear * dt;
    return T;
  }
};

}  // namespace ply_slam
