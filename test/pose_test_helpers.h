#pragma once

// Camera, poses and pose errors shared by the pose-optimisation tests.
#include <Eigen/Geometry>
#include <random>

#include "ply_slam/common/pinhole_camera.h"

namespace ply_slam::test {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDegreesPerRadian = 180.0 / kPi;

// TUM fr1 intrinsics, undistorted pixels, a small sensor noise: sigma_Z = 1.6 mm at 1 m,
// 6.3 mm at 4 m.
inline PinholeCamera makeCamera() {
  PinholeCamera camera;
  camera.fx = 517.3;
  camera.fy = 516.5;
  camera.cx = 318.6;
  camera.cy = 255.3;
  camera.width = 640;
  camera.height = 480;
  camera.depth_noise = DepthNoiseModel{2.5e-6, 0.0, 1.0e-7};
  return camera;
}

inline Eigen::Isometry3d makePose(const Eigen::Vector3d& axis, double angle_deg,
                                  const Eigen::Vector3d& t) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() =
      Eigen::AngleAxisd(angle_deg / kDegreesPerRadian, axis.normalized()).toRotationMatrix();
  T.translation() = t;
  return T;
}

// 20 deg about a tilted axis, translated (0.3, -0.1, 0.2) m.
inline Eigen::Isometry3d truePose() { return makePose({0.3, 1.0, -0.4}, 20.0, {0.3, -0.1, 0.2}); }

inline double rotationErrorDeg(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return Eigen::AngleAxisd(a.rotation() * b.rotation().transpose()).angle() * kDegreesPerRadian;
}

// Distance of the camera centres: the quantity a trajectory error measures.
inline double translationError(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return (a.inverse().translation() - b.inverse().translation()).norm();
}

// The true pose moved by 5 cm and turned by 3 deg, in random directions.
inline Eigen::Isometry3d perturbed(const Eigen::Isometry3d& T, unsigned seed) {
  std::mt19937 rng(seed + 1000);
  std::normal_distribution<double> gauss(0.0, 1.0);
  const Eigen::Vector3d axis(gauss(rng), gauss(rng), gauss(rng));
  const Eigen::Vector3d shift(gauss(rng), gauss(rng), gauss(rng));
  return makePose(axis, 3.0, 0.05 * shift.normalized()) * T;
}

}  // namespace ply_slam::test
