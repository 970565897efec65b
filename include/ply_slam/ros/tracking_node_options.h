#pragma once

#include <ros/node_handle.h>

#include <cstddef>
#include <string>

#include "ply_slam/system/system_config.h"

namespace ply_slam {

// tracking_node's private parameters, read in one place (trackingNodeOptionsFromParams).
// launch/tracking.launch states each one with its default; the initialisers here are the
// fallbacks for a node started without it.
struct TrackingNodeOptions {
  SystemConfig config;  // ~config: required (a config/*.yaml loaded there)
  std::string rgb_topic = "rgb/image";
  std::string depth_topic = "depth/image";
  std::string camera_info_topic = "rgb/camera_info";
  bool use_camera_info = true;     // false: the config's intrinsics even when camera_info comes
  double depth_16u_scale = 0.001;  // m per unit of 16UC1 depth
  int sync_queue_size = 10;        // >= 1
  double sync_slop = 0.02;         // s between rgb and depth stamps at most
  // The shortest time between two images of one stream (s; 0 = unknown): lets the synchroniser
  // emit a pair as soon as no later message could pair better.
  double sync_min_period = 0.0;
  // s of quiet after which the newest unpaired rgb + depth are tracked as a pair (0 = never).
  double sync_flush_after = 0.5;
  // s a frame may wait for the tracker: older ones are dropped, the oldest first (a live camera
  // cannot wait); 0 = every frame waits (a bag replayed faster than it was recorded).
  double frame_max_age = 0.3;
  std::string world_frame = "map";
  bool publish_images = true;
  // s (wall clock) between two ~path messages at least: the whole path is in each, up to
  // 1.5 MB, too much to send with every frame to a remote rviz.
  double path_period = 1.0;
  std::string map;  // a saved map folder to localise in; "" = a new map
  bool localisation_only = true;
  bool mapping_thread = true;  // the mapping side beside tracking, not after each keyframe
  // The mapping side in mapping_node (~map_keyframes there): keyframes go out as jobs on
  // ~mapping_job, the tracker's copy of the map follows the updates on mapper_update_topic.
  bool mapping_apart = true;
  std::string mapper_update_topic = "mapping_node/map_update";
  // ~mapping_apart: asked at the start for the mapping side's map; when it is not empty (this
  // node restarted) the tracker takes it over instead of ~map.
  std::string mapper_map_service = "mapping_node/map_for_tracker";
};

// Throws ConfigError for a missing or bad ~config (as configFromParams) and std::invalid_argument
// "~NAME ..." for a bad parameter (badParam), e.g. a ~map folder without a map file.
TrackingNodeOptions trackingNodeOptionsFromParams(const ros::NodeHandle& pnh);

}  // namespace ply_slam
