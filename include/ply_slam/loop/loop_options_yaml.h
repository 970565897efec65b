#pragma once

#include <yaml-cpp/yaml.h>

#include "ply_slam/common/config_section.h"
#include "ply_slam/loop/loop_options.h"

namespace ply_slam {

// Reads the `loop:` section of a config file (an absent or null section gives the defaults)
// with the config's own section reader. Keys are LoopOptions' member names. An unknown key, a
// value of the wrong type or out of range throws ConfigError naming the file and "loop.<key>". The
// depth noise is not read here: it belongs to the camera (camera.depth_noise), the caller copies it
// into depth_noise. Not named plain fromYaml: free functions cannot overload on the return type
// alone, and other modules' options will want a reader too.
LoopOptions readLoopOptions(ConfigSection loop_section);
// The same for a bare node (no file to name).
LoopOptions loopOptionsFromYaml(const YAML::Node& loop_section);

}  // namespace ply_slam
