#pragma once

#include <Eigen/Geometry>
#include <vector>

#include "ply_slam/common/pinhole_camera.h"
#include "ply_slam/synth/rendered_frame.h"
#include "ply_slam/synth/scene.h"

namespace ply_slam {

// What one ray sees.
struct RayHit {
  int surface = -1;                                  // quad index, -1 = nothing
  double depth = 0.0;                                // z in the camera frame
  Eigen::Vector2d coords = Eigen::Vector2d::Zero();  // metres along the quad's u, v axes
  Eigen::Vector3d world = Eigen::Vector3d::Zero();
};

// CPU ray caster for scenes of textured quads. Per frame the quads are binned into 16x16
// pixel tiles by their projected (near-clipped) outline, so each ray is tested against the
// few quads that can cover it; rows of tiles run in parallel (cv::parallel_for_).
class RayCaster {
 public:
  explicit RayCaster(const PinholeCamera& camera, double near = 0.05);

  // Renders `quads` (e.g. Scene::quadsAt(t)) with the scene's textures and lighting from
  // camera pose T_wc (x right, y down, z forward).
  RenderedFrame render(const Scene& scene, const std::vector<Quad>& quads,
                       const Eigen::Isometry3d& T_wc, bool antialias = true) const;

  // The nearest quad along the ray through pixel (u, v) (any real position), tested
  // against every quad: for checks, not speed.
  RayHit cast(const std::vector<Quad>& quads, const Eigen::Isometry3d& T_wc,
              const Eigen::Vector2d& uv) const;

  const PinholeCamera& camera() const { return camera_; }

 private:
  PinholeCamera camera_;
  double near_;
};

}  // namespace ply_slam
