#pragma once

#include <Eigen/Geometry>
#include <array>
#include <vector>

#include "ply_slam/synth/quad.h"
#include "ply_slam/synth/segment3.h"
#include "ply_slam/synth/texture.h"

namespace ply_slam {

// Faces of a box in its own frame, in this order (x forward, y left, z up).
enum BoxFace { kBoxFront = 0, kBoxBack, kBoxLeft, kBoxRight, kBoxTop, kBoxBottom };

// A box of `size` (x, y, z) standing on the xy-plane of `pose` (local z from 0 to size.z,
// centred in x and y). Vertical faces get u = right and v = down as seen from outside, so a
// photograph mapped onto them is upright and unmirrored.
std::vector<Quad> makeBox(const Eigen::Isometry3d& pose, const Eigen::Vector3d& size,
                          const std::array<SurfaceMaterial, 6>& faces, int instance = 0);
std::vector<Quad> makeBox(const Eigen::Isometry3d& pose, const Eigen::Vector3d& size,
                          const SurfaceMaterial& all_faces, int instance = 0);
// An axis-aligned box from its minimum and maximum corner.
std::vector<Quad> makeAlignedBox(const Eigen::Vector3d& min, const Eigen::Vector3d& max,
                                 const SurfaceMaterial& all_faces);
// The 12 edges of such a box.
std::vector<Segment3> boxEdges(const Eigen::Isometry3d& pose, const Eigen::Vector3d& size);
std::vector<Segment3> alignedBoxEdges(const Eigen::Vector3d& min, const Eigen::Vector3d& max);

// A vertical rectangle seen from the side its `facing` (horizontal) normal points to: u runs
// to the viewer's right, v downwards; `centre` is its middle.
Quad makeUprightRect(const Eigen::Vector3d& centre, const Eigen::Vector3d& facing, double width,
                     double height, const SurfaceMaterial& material);
// The 4 border segments of a quad.
std::vector<Segment3> quadEdges(const Quad& quad);

// The whole photograph stretched over a face of width x height metres.
SurfaceMaterial fittedPhoto(int texture_index, const Texture& texture, double width, double height,
                            const cv::Vec3f& colour = {1.0f, 1.0f, 1.0f});
// The photograph tiled with a metric scale (texels per metre).
SurfaceMaterial tiledPhoto(int texture_index, double texels_per_metre,
                           const cv::Vec3f& colour = {1.0f, 1.0f, 1.0f});

}  // namespace ply_slam
