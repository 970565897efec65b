#pragma once

#include "ply_slam/common/config_section.h"
#include "ply_slam/mapping/local_mapping_options.h"

namespace ply_slam {

// Reads the `mapping:` section (absent: the defaults): fuse_radius_px,
// fuse_max_descriptor_distance and bundle_solver, a map of solver settings (readSolverOptions).
// window_keyframes and chi2_outlier are not read here: they are tracking's keys
// (local_map_keyframes, chi2_outlier), the caller copies them in. Unknown keys and values out of
// range throw ConfigError naming the file and key.
LocalMappingOptions readLocalMappingOptions(ConfigSection section);

}  // namespace ply_slam
