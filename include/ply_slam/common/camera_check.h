#pragma once

#include <optional>
#include <string>

#include "ply_slam/common/pinhole_camera.h"

namespace ply_slam {

// What is wrong with a camera's numbers, by the config key of the number at fault
// ("fx", "distortion", "depth_noise.alpha"). A NaN, an infinity or an absurd value (a focal
// length of 1e-300 px) sends points to infinity and must be refused where the camera comes
// in: the config, a camera_info, a keyframe message.
struct CameraProblem {
  std::string key;
  std::string what;  // e.g. "must be a finite number in [1, 100000] px, got nan"
};

std::optional<CameraProblem> findCameraProblem(const PinholeCamera& camera);

}  // namespace ply_slam
