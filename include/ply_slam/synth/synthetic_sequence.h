#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <string>

#include "ply_slam/common/pinhole_camera.h"
#include "ply_slam/synth/camera_path.h"
#include "ply_slam/synth/ray_caster.h"
#include "ply_slam/synth/scene_library.h"
#include "ply_slam/synth/sensor_noise.h"

namespace ply_slam {

struct SynthOptions {
  SceneKind scene = SceneKind::kOffice;
  int walkers = 0;
  int frames = 300;
  bool loop = false;   // the camera ends where it started
  bool noise = false;  // sensor noise on depth and colour; else exact images
  uint64_t seed = 1;
  double fps = 30.0;
  std::string texture_dir = kDefaultTextureDir;
};

// The camera of every synthetic sequence: 640x480, fx = fy = 525, centre (319.5, 239.5), no
// distortion, depth factor 5000.
PinholeCamera syntheticCamera();

// A synthetic RGB-D sequence: scene, camera path and renderer, frame by frame on demand.
// Camera: 640x480, fx = fy = 525, centre (319.5, 239.5), no distortion, depth factor 5000.
class SyntheticSequence {
 public:
  explicit SyntheticSequence(const SynthOptions& options);

  const SynthOptions& options() const { return options_; }
  const Scene& scene() const { return setup_.scene; }
  const CameraPath& path() const { return path_; }
  const PinholeCamera& camera() const { return caster_.camera(); }
  const RayCaster& caster() const { return caster_; }
  const SensorNoise& noise() const { return noise_; }

  int size() const { return options_.frames; }
  double time(int i) const { return i / options_.fps; }                 // s since the first frame
  double stamp(int i) const;                                            // TUM-like absolute stamp
  Eigen::Isometry3d pose(int i) const { return path_.poseAtFrame(i); }  // T_wc

  // Frame i as the sensor sees it (with noise when enabled; surface maps stay exact).
  RenderedFrame render(int i) const;
  // Frame i exact, with or without the walkers.
  RenderedFrame renderExact(int i, bool with_walkers = true) const;

  // The camera as written to camera.yaml: depth noise and range of the generator settings.
  PinholeCamera sensorCamera() const;

 private:
  SynthOptions options_;
  SceneSetup setup_;
  CameraPath path_;
  RayCaster caster_;
  SensorNoise noise_;
};

}  // namespace ply_slam
