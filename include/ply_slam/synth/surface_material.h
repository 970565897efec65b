#pragma once

#include <Eigen/Core>
#include <opencv2/core.hpp>

namespace ply_slam {

// How a quad looks: a plain reflectance or a photograph mapped with metric scale, so that a
// picture 1 m wide stays 1 m wide at every distance and features scale as in a real room.
struct SurfaceMaterial {
  int texture = -1;                            // index into Scene::textures(); -1 = plain colour
  cv::Vec3f colour{0.8f, 0.8f, 0.8f};          // BGR reflectance in [0, 1]; multiplies the texture
  Eigen::Vector2d texel_origin{0.0, 0.0};      // texel (s, t) at the quad's origin corner
  Eigen::Vector2d texels_per_metre{0.0, 0.0};  // along the quad's u and v axes
  bool repeat = false;                         // tile the photograph, else clamp at its border

  static SurfaceMaterial plain(const cv::Vec3f& colour) {
    SurfaceMaterial m;
    m.colour = colour;
    return m;
  }
};

}  // namespace ply_slam
