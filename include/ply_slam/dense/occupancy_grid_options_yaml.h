#pragma once

#include "ply_slam/common/config_section.h"
#include "ply_slam/dense/occupancy_grid_options.h"

namespace ply_slam {

// Reads the `grid:` section (absent: the defaults); keys are the options' member names.
// Unknown keys and values out of range throw ConfigError naming the file and key.
OccupancyGridOptions readOccupancyGridOptions(ConfigSection section);

}  // namespace ply_slam
