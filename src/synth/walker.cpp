#include "ply_slam/synth/walker.h"

#include <array>
#include <cmath>

#include "ply_slam/synth/quad_builder.h"

namespace ply_slam {

Walker::Walker(int instance, const Path& path, const Eigen::Vector3d& size,
               const SurfaceMaterial& sides, const SurfaceMaterial& top)
    : instance_(instance), path_(path), size_(size), sides_(sides), top_(top) {}

double Walker::pathLength() const { return 2.0 * path_.straight + 2.0 * M_PI * path_.radius; }

Eigen::Isometry3d Walker::pose(double t) const {
  const double L = path_.straight, r = path_.radius, arc = M_PI * r;
  double s = std::fmod(path_.start + path_.speed * t, pathLength());
  if (s < 0) s += pathLength();
  // Position and heading in the loop's own frame: the first straight runs along +x at y = -r.
  Eigen::Vector2d p;
  double yaw;
  if (s < L) {
    p = {-0.5 * L + s, -r};
    yaw = 0.0;
  } else if (s < L + arc) {
    const double a = -0.5 * M_PI + (s - L) / r;
    p = {0.5 * L + r * std::cos(a), r * std::sin(a)};
    yaw = a + 0.5 * M_PI;
  } else if (s < 2 * L + arc) {
    p = {0.5 * L - (s - L - arc), r};
    yaw = M_PI;
  } else {
    const double a = 0.5 * M_PI + (s - 2 * L - arc) / r;
    p = {-0.5 * L + r * std::cos(a), r * std::sin(a)};
    yaw = a + 0.5 * M_PI;
  }
  const Eigen::Rotation2Dd heading(path_.heading);
  const Eigen::Vector2d world = path_.centre + heading * p;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() =
      Eigen::AngleAxisd(yaw + path_.heading, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  pose.translation() << world.x(), world.y(), 0.0;
  return pose;
}

std::vector<Quad> Walker::quads(double t) const {
  std::array<SurfaceMaterial, 6> faces;
  faces.fill(sides_);
  faces[kBoxTop] = top_;
  faces[kBoxBottom] = top_;
  return makeBox(pose(t), size_, faces, instance_);
}

}  // namespace ply_slam
