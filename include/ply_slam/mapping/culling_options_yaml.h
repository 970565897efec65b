#pragma once

#include "ply_slam/common/config_section.h"
#include "ply_slam/mapping/culling_options.h"

namespace ply_slam {

// Reads the `culling:` section (absent: the defaults); keys are the options' member names
// prefixed keyframe_ or point_. Unknown keys and values out of range throw ConfigError naming
// the file and key.
CullingOptions readCullingOptions(ConfigSection section);

}  // namespace ply_slam
