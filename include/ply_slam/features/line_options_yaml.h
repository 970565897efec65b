#pragma once

#include "ply_slam/common/config_section.h"
#include "ply_slam/features/line_options.h"

namespace ply_slam {

// Reads the `lines:` section (absent: the defaults); keys are the options' member names, the
// balance and the detector as their words. Unknown keys, unknown words and values out of range
// throw ConfigError naming the file and key.
LineOptions readLineOptions(ConfigSection section);

}  // namespace ply_slam
