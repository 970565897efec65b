#pragma once

#include "ply_slam/common/config_section.h"
#include "ply_slam/dynamic/dynamic_options.h"

namespace ply_slam {

// Reads the `dynamic:` section (absent: the defaults). The Delaunay check's and the filter's keys
// sit flat in it beside the rejector's own. Unknown keys, an unknown mode and values out of range
// throw ConfigError naming the file and key.
DynamicOptions readDynamicOptions(ConfigSection section);

}  // namespace ply_slam
