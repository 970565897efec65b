#pragma once

#include <yaml-cpp/yaml.h>

#include "ply_slam/loop/loop_options.h"

namespace ply_slam {

// Reads the `loop:` section of a config file (pass that node; an absent or null node gives
// the defaults). Keys are LoopOptions' member names. An unknown key, a value of the wrong type
// or out of range throws std::runtime_error naming "loop.<key>". The depth noise is not read
// here: it belongs to the camera (camera.depth_noise), the caller copies it into depth_noise.
// Not named plain fromYaml: free functions cannot overload on the return type alone, and other
// modules' options will want a reader too.
LoopOptions loopOptionsFromYaml(const YAML::Node& loop_section);

}  // namespace ply_slam
