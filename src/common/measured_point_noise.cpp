#include "ply_slam/common/measured_point_noise.h"

#include <cmath>

namespace ply_slam {

MeasuredPointNoise::MeasuredPointNoise(const PinholeCamera& camera, double pixel_sigma)
    : fx_(camera.fx), fy_(camera.fy), depth_noise_(camera.depth_noise), pixel_sigma_(pixel_sigma) {}

Eigen::Matrix3d MeasuredPointNoise::covariance(const Eigen::Vector3d& p,
                                               const Eigen::Vector2d& slope) const {
  const double z = p.z();
  Eigen::Matrix3d J;
  J << z / fx_, 0.0, p.x() / z,  //
      0.0, z / fy_, p.y() / z,   //
      0.0, 0.0, 1.0;
  // The depth follows the pixel along the slope: dP/du gains (dP/dZ) s_u, dP/dv (dP/dZ) s_v.
  J.col(0) += J.col(2) * slope.x();
  J.col(1) += J.col(2) * slope.y();
  const double s2 = pixel_sigma_ * pixel_sigma_;
  const Eigen::Vector3d lambda(s2, s2, depth_noise_.variance(z));
  return J * lambda.asDiagonal() * J.transpose();
}

double MeasuredPointNoise::varianceAlong(const Eigen::Vector3d& p, const Eigen::Vector3d& d,
                                         const Eigen::Vector2d& slope) const {
  const double z = p.z();
  // dP/dZ = P / Z; dP/du = (Z / fx, 0, 0) + (P / Z) s_u; dP/dv = (0, Z / fy, 0) + (P / Z) s_v.
  const double along_ray = d.dot(p / z);
  const double du = d.x() * z / fx_ + along_ray * slope.x();
  const double dv = d.y() * z / fy_ + along_ray * slope.y();
  return along_ray * along_ray * depth_noise_.variance(z) +
         pixel_sigma_ * pixel_sigma_ * (du * du + dv * dv);
}

}  // namespace ply_slam
