#include "ply_slam/ros/tracking_node_options.h"

#include <algorithm>
#include <filesystem>

#include "ply_slam/ros/config_from_params.h"
#include "ply_slam/ros/node_params.h"
#include "ply_slam/system/system.h"

namespace ply_slam {

TrackingNodeOptions trackingNodeOptionsFromParams(const ros::NodeHandle& pnh) {
  TrackingNodeOptions o;
  o.config = configFromParams(pnh, "config");
  readParam(pnh, "rgb_topic", &o.rgb_topic);
  readParam(pnh, "depth_topic", &o.depth_topic);
  readParam(pnh, "camera_info_topic", &o.camera_info_topic);
  readParam(pnh, "use_camera_info", &o.use_camera_info);
  readParam(pnh, "depth_16u_scale", &o.depth_16u_scale);
  readParam(pnh, "sync_queue_size", &o.sync_queue_size);
  o.sync_queue_size = std::max(1, o.sync_queue_size);
  readParam(pnh, "sync_slop", &o.sync_slop);
  readParam(pnh, "sync_min_period", &o.sync_min_period);
  readParam(pnh, "sync_flush_after", &o.sync_flush_after);
  readParam(pnh, "frame_max_age", &o.frame_max_age);
  if (!(o.frame_max_age >= 0)) badParam("frame_max_age", "must be >= 0 s (0: no frame dropped)");
  readParam(pnh, "world_frame", &o.world_frame);
  readParam(pnh, "publish_images", &o.publish_images);
  readPeriod(pnh, "path_period", &o.path_period);
  readParam(pnh, "map", &o.map);
  readParam(pnh, "localisation_only", &o.localisation_only);
  readParam(pnh, "mapping_thread", &o.mapping_thread);
  readParam(pnh, "mapping_apart", &o.mapping_apart);
  readParam(pnh, "mapper_update_topic", &o.mapper_update_topic);
  readParam(pnh, "mapper_map_service", &o.mapper_map_service);
  // Said at the start, not at the first frame (the system is made then, from camera_info).
  const std::filesystem::path map_file = std::filesystem::path(o.map) / System::kMapFileName;
  if (!o.map.empty() && !std::filesystem::is_regular_file(map_file))
    badParam("map", "has no map file " + map_file.string());
  return o;
}

}  // namespace ply_slam
