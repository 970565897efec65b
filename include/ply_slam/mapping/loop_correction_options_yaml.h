#pragma once

#include "ply_slam/common/config_section.h"
#include "ply_slam/mapping/loop_correction_options.h"

namespace ply_slam {

// Reads the `loop_correction:` section (absent: the defaults); keys are the options' member
// names, the pose graph's prefixed pose_graph_. Unknown keys and values out of range throw
// ConfigError naming the file and key.
LoopCorrectionOptions readLoopCorrectionOptions(ConfigSection section);

}  // namespace ply_slam
