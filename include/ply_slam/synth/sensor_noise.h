#pragma once

#include <cstdint>

#include "ply_slam/common/pinhole_camera.h"
#include "ply_slam/synth/rendered_frame.h"

namespace ply_slam {

// What a structured-light RGB-D sensor does to a perfect rendering.
struct SensorNoiseParams {
  DepthNoiseModel depth;    // sigma_Z^2 = alpha Z^2 + beta Z + gamma (Kinect-like default)
  double min_range = 0.4;   // m; nearer: no depth (the projector pattern is out of focus)
  double max_range = 6.0;   // m; farther: no depth
  double edge_jump = 0.04;  // m, plus edge_jump_per_metre * Z: a larger step to a
  double edge_jump_per_metre = 0.02;  // neighbour leaves the pixel without depth (shadow)
  double rgb_sigma = 2.0;             // grey levels, per channel
  double blur_sigma = 0.6;            // px, optics
};

// What the tracker should assume for exact rendered depth: the 1/5000 m quantum (variance
// q^2 / 12) and, dominating it, reading the depth of a sub-pixel keypoint at a pixel centre on
// a slanted surface: about 0.3 px times z / f per pixel at 45 degrees, sigma_Z ~ 0.55 mm * Z.
inline const DepthNoiseModel kExactDepthNoise{3.0e-7, 0.0, 3.3e-9};

// Applies the sensor model to a frame in place: Gaussian depth noise per pixel, holes at depth
// edges and outside the range, blurred and noisy colour. Seeded per frame: deterministic.
class SensorNoise {
 public:
  explicit SensorNoise(const SensorNoiseParams& params = SensorNoiseParams()) : params_(params) {}

  void apply(RenderedFrame& frame, uint64_t seed) const;
  const SensorNoiseParams& params() const { return params_; }

 private:
  SensorNoiseParams params_;
};

}  // namespace ply_slam
