#pragma once

#include "ply_slam/common/config_section.h"
#include "ply_slam/tracking/tracking_options.h"

namespace ply_slam {

// Reads the `tracking:` section (absent: the defaults); keys are the options' member names,
// pose_solver a map of solver settings (readSolverOptions). Unknown keys and values out of range
// throw ConfigError naming the file and key.
TrackingOptions readTrackingOptions(ConfigSection section);

}  // namespace ply_slam
