#pragma once

#include <string>
#include <vector>

#include "ply_slam/common/config_error.h"
#include "ply_slam/common/pinhole_camera.h"
#include "ply_slam/dense/dense_options.h"
#include "ply_slam/dense/occupancy_grid_options.h"
#include "ply_slam/dynamic/dynamic_options.h"
#include "ply_slam/features/line_options.h"
#include "ply_slam/features/orb_options.h"
#include "ply_slam/loop/loop_options.h"
#include "ply_slam/mapping/culling_options.h"
#include "ply_slam/mapping/local_mapping_options.h"
#include "ply_slam/mapping/loop_correction_options.h"
#include "ply_slam/mapping/mapper_options.h"
#include "ply_slam/semantic/yolo_options.h"
#include "ply_slam/tracking/tracking_options.h"

namespace ply_slam {

// The whole config file: one options struct per section, each read by its module's reader
// (*_options_yaml.h) and handed to the components of that module alone.
struct SystemConfig {
  std::string source_path;  // the file it was loaded from
  std::string yaml;         // the document as parsed (a tracker apart sends it with its jobs)
  PinholeCamera camera;
  OrbOptions orb;
  LineOptions lines;
  TrackingOptions tracking;
  YoloOptions segmentation;
  DynamicOptions dynamic;
  DenseOptions dense;
  // Local mapping (mapping module): the `mapping:` section, with tracking's local-map window
  // and outlier bound.
  LocalMappingOptions mapping;
  OccupancyGridOptions grid;  // 2D occupancy grid from the octree (dense module)
  LoopOptions loop;           // place recognition (loop module); its depth noise is the camera's
  LoopCorrectionOptions loop_correction;  // closing an accepted loop (mapping module)
  CullingOptions culling;                 // retiring keyframes and points (mapping module)
};

// Loads a YAML config. Unknown keys, missing required keys (camera intrinsics, size) and
// out-of-range values throw ConfigError naming the file and key.
SystemConfig loadConfig(const std::string& path);
// The same from YAML text (the ROS nodes rebuild it from the parameter server); errors name
// `source_name` where loadConfig names the file.
SystemConfig loadConfigFromString(const std::string& yaml_text, const std::string& source_name);

// What the mapping side takes of the config.
MapperOptions mapperOptions(const SystemConfig& config);
// The keys of what the mapping side takes (mapperOptions, and the ORB pyramid its keyframes'
// features come in) whose values differ between the two configs' documents, dotted
// ("orb.num_levels"); numbers compare as numbers. A key given in one and left to its default in
// the other counts as differing.
std::vector<std::string> mappingSettingsThatDiffer(const SystemConfig& a, const SystemConfig& b);
// The config with another camera (a camera_info's, a tracker's), everywhere it is used.
void useCamera(SystemConfig& config, const PinholeCamera& camera);

}  // namespace ply_slam
