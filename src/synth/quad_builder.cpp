#include "ply_slam/synth/quad_builder.h"

namespace ply_slam {
namespace {

// A face with outward normal `normal` (local frame), centred at `centre`, spanned by `right`
// and `down` (full lengths).
Quad face(const Eigen::Isometry3d& pose, const Eigen::Vector3d& centre,
          const Eigen::Vector3d& right, const Eigen::Vector3d& down,
          const SurfaceMaterial& material, int instance) {
  Quad q;
  q.origin = pose * (centre - 0.5 * right - 0.5 * down);
  q.axis_u = pose.linear() * right;
  q.axis_v = pose.linear() * down;
  q.material = material;
  q.instance = instance;
  return q;
}

}  // namespace

std::vector<Quad> makeBox(const Eigen::Isometry3d& pose, const Eigen::Vector3d& size,
                          const std::array<SurfaceMaterial, 6>& faces, int instance) {
  const double hx = 0.5 * size.x(), hy = 0.5 * size.y(), sz = size.z();
  const Eigen::Vector3d ex = Eigen::Vector3d::UnitX(), ey = Eigen::Vector3d::UnitY(),
                        ez = Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d down = -sz * ez;
  std::vector<Quad> quads;
  // Seen from outside a face with normal n, the viewer's right is (-n) x z.
  quads.push_back(face(pose, {hx, 0, 0.5 * sz}, size.y() * ey, down, faces[kBoxFront], instance));
  quads.push_back(face(pose, {-hx, 0, 0.5 * sz}, -size.y() * ey, down, faces[kBoxBack], instance));
  quads.push_back(face(pose, {0, hy, 0.5 * sz}, -size.x() * ex, down, faces[kBoxLeft], instance));
  quads.push_back(face(pose, {0, -hy, 0.5 * sz}, size.x() * ex, down, faces[kBoxRight], instance));
  // Top seen from above with local +x up in the picture; bottom seen from below.
  quads.push_back(face(pose, {0, 0, sz}, -size.y() * ey, -size.x() * ex, faces[kBoxTop], instance));
  quads.push_back(
      face(pose, {0, 0, 0}, size.y() * ey, -size.x() * ex, faces[kBoxBottom], instance));
  return quads;
}

std::vector<Quad> makeBox(const Eigen::Isometry3d& pose, const Eigen::Vector3d& size,
                          const SurfaceMaterial& all_faces, int instance) {
  std::array<SurfaceMaterial, 6> faces;
  faces.fill(all_faces);
  return makeBox(pose, size, faces, instance);
}

std::vector<Quad> makeAlignedBox(const Eigen::Vector3d& min, const Eigen::Vector3d& max,
                                 const SurfaceMaterial& all_faces) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() << 0.5 * (min.x() + max.x()), 0.5 * (min.y() + max.y()), min.z();
  return makeBox(pose, max - min, all_faces);
}

std::vector<Segment3> boxEdges(const Eigen::Isometry3d& pose, const Eigen::Vector3d& size) {
  const double hx = 0.5 * size.x(), hy = 0.5 * size.y(), sz = size.z();
  auto corner = [&](int i) {
    return pose * Eigen::Vector3d((i & 1) ? hx : -hx, (i & 2) ? hy : -hy, (i & 4) ? sz : 0.0);
  };
  std::vector<Segment3> edges;
  // Corners differing in exactly one bit share an edge.
  for (int i = 0; i < 8; ++i)
    for (int bit = 1; bit < 8; bit <<= 1)
      if (!(i & bit)) edges.push_back({corner(i), corner(i | bit)});
  return edges;
}

std::vector<Segment3> alignedBoxEdges(const Eigen::Vector3d& min, const Eigen::Vector3d& max) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() << 0.5 * (min.x() + max.x()), 0.5 * (min.y() + max.y()), min.z();
  return boxEdges(pose, max - min);
}

Quad makeUprightRect(const Eigen::Vector3d& centre, const Eigen::Vector3d& facing, double width,
                     double height, const SurfaceMaterial& material) {
  const Eigen::Vector3d n = Eigen::Vector3d(facing.x(), facing.y(), 0.0).normalized();
  const Eigen::Vector3d right = (-n).cross(Eigen::Vector3d::UnitZ()).normalized();
  Quad q;
  q.axis_u = width * right;
  q.axis_v = -height * Eigen::Vector3d::UnitZ();
  q.origin = centre - 0.5 * q.axis_u - 0.5 * q.axis_v;
  q.material = material;
  return q;
}

std::vector<Segment3> quadEdges(const Quad& quad) {
  std::vector<Segment3> edges;
  for (int k = 0; k < 4; ++k) edges.push_back({quad.corner(k), quad.corner(k + 1)});
  return edges;
}

SurfaceMaterial fittedPhoto(int texture_index, const Texture& texture, double width, double height,
                            const cv::Vec3f& colour) {
  SurfaceMaterial m;
  m.texture = texture_index;
  m.colour = colour;
  m.texels_per_metre = {texture.width() / width, texture.height() / height};
  return m;
}

SurfaceMaterial tiledPhoto(int texture_index, double texels_per_metre, const cv::Vec3f& colour) {
  SurfaceMaterial m;
  m.texture = texture_index;
  m.colour = colour;
  m.texels_per_metre = {texels_per_metre, texels_per_metre};
  m.repeat = true;
  return m;
}

}  // namespace ply_slam
