#pragma once

#include <string>

#include "ply_slam/synth/camera_path.h"
#include "ply_slam/synth/scene.h"

namespace ply_slam {

// The photographs of the Debian package opencv-doc.
inline const char* const kDefaultTextureDir = "/usr/share/doc/opencv-doc/examples/data";

enum class SceneKind {
  kOffice,      // posters, a rug, desk, shelf, door: many corners and lines
  kLowTexture,  // the same room in plain white with two small pictures: points are scarce
  kCorridor,    // 12 m long, 2.2 m wide, door frames on both sides: long parallel lines
  kRing,        // a 2 m wide corridor around a 4 x 2 m block, walked once round: a real loop
};

bool parseSceneKind(const std::string& text, SceneKind* kind);
std::string sceneKindName(SceneKind kind);
// Frames at 30 Hz the scene's camera path is made for: the ring's circuit takes the whole
// sequence, so its walking speed depends on the length (1500 frames: 0.38 m/s).
int defaultFrames(SceneKind kind);

// A scene with the camera motion that suits it.
struct SceneSetup {
  Scene scene;
  CameraPathSpec camera;
};

// Builds a scene with `walkers` people (instance ids 1..walkers) walking in it. Throws
// std::runtime_error naming the file when a photograph cannot be read from texture_dir, and
// std::invalid_argument for walkers in the ring (its corridor has no room to pass the camera).
SceneSetup buildScene(SceneKind kind, int walkers, const std::string& texture_dir);

}  // namespace ply_slam
