#pragma once

#include "ply_slam/common/config_section.h"
#include "ply_slam/dense/dense_options.h"

namespace ply_slam {

// Reads the `dense:` section (absent: the defaults); keys are the options' member names, the
// colour mode as its word. Unknown keys, an unknown word and values out of range throw
// ConfigError naming the file and key.
DenseOptions readDenseOptions(ConfigSection section);

}  // namespace ply_slam
