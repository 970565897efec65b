#pragma once

#include "ply_slam/common/config_section.h"
#include "ply_slam/semantic/yolo_options.h"

namespace ply_slam {

// Reads the `segmentation:` section (absent: the defaults, no model). Keys: model, classes (the
// two paths) and the other members' names; backend and target as the words below. Unknown keys
// and values out of range throw ConfigError naming the file and key.
YoloOptions readYoloOptions(ConfigSection section);

// The config's words for a backend / target ("opencv", "cpu", ...).
const char* dnnBackendWord(DnnBackend backend);
const char* dnnTargetWord(DnnTarget target);

}  // namespace ply_slam
