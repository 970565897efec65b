#pragma once

#include "ply_slam/common/config_section.h"
#include "ply_slam/features/orb_options.h"

namespace ply_slam {

// Reads the `orb:` section (absent: the defaults); keys are the options' member names.
// Unknown keys and values out of range throw ConfigError naming the file and key.
OrbOptions readOrbOptions(ConfigSection section);

}  // namespace ply_slam
