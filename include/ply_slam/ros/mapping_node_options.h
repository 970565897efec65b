#pragma once

#include <ros/node_handle.h>

#include <Eigen/Geometry>
#include <optional>
#include <string>

#include "ply_slam/system/system_config.h"

namespace ply_slam {

// mapping_node's private parameters, read in one place (mappingNodeOptionsFromParams).
// launch/mapping.launch states each one with its default; the initialisers here are the
// fallbacks for a node started without it.
struct MappingNodeOptions {
  SystemConfig config;  // ~config: required, as tracking_node's (dense, grid, dynamic sections)
  // tf frames, without leading slashes. world_frame: the tracker's poses and the map (fallback:
  // map_frame); odom_frame "" = no odometry.
  std::string map_frame = "map";
  std::string world_frame;
  std::string odom_frame;
  std::string camera_frame = "camera_color_optical_frame";
  // ~world_in_map (x y z yaw pitch roll, m and rad, as tf2_ros static_transform_publisher): a
  // fixed placement of the world in map_frame, e.g. to show the optical-frame world of a TUM bag
  // upright. Only without odometry and with world_frame unlike map_frame; [] = none.
  std::optional<Eigen::Isometry3d> world_in_map;
  // A saved map being localised in: its world_in_map.txt places the world; with map_keyframes
  // the mapping side starts from its map file (the tracker apart loads the same).
  std::string map;
  double dense_publish_period = 2.0;  // s, > 0
  double grid_publish_period = 2.0;   // s, > 0
  std::string keyframe_topic = "tracking_node/keyframe";
  std::string pose_topic = "tracking_node/pose";
  std::string map_update_topic = "tracking_node/map_update";
  std::string map_snapshot_topic = "tracking_node/map_snapshot";
  std::string resend_service = "tracking_node/resend_map";
  std::string tracker_save_map_service = "tracking_node/save_map";
  // With map_keyframes: asked at the start and after a missed job; the tracker hands over its
  // copy of the map, from which the mapping side starts anew.
  std::string hand_over_service = "tracking_node/hand_over_map";
  // Run the mapping side here (a MappingSide on a thread of its own) on the jobs of a tracker
  // with ~mapping_apart, and send it the updates (~map_update); false: keep a copy of the map
  // the tracking process maps (keyframe_topic, map_update_topic).
  bool map_keyframes = true;
  std::string mapping_job_topic = "tracking_node/mapping_job";
  // With map_keyframes: the tracker asks here for the updates it missed, from the number given.
  std::string updates_wanted_topic = "tracking_node/updates_wanted";
};

// Throws ConfigError for a missing or bad ~config (as configFromParams) and std::invalid_argument
// "~NAME ..." for a bad parameter (badParam).
MappingNodeOptions mappingNodeOptionsFromParams(const ros::NodeHandle& pnh);

}  // namespace ply_slam
