#include "ply_slam/ros/mapping_node_options.h"

#include <filesystem>
#include <vector>

#include "ply_slam/ros/config_from_params.h"
#include "ply_slam/ros/node_params.h"
#include "ply_slam/system/system.h"

namespace ply_slam {
namespace {

Eigen::Isometry3d fromXyzYawPitchRoll(const std::vector<double>& v) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = Eigen::Vector3d(v[0], v[1], v[2]);
  T.linear() = (Eigen::AngleAxisd(v[3], Eigen::Vector3d::UnitZ()) *
                Eigen::AngleAxisd(v[4], Eigen::Vector3d::UnitY()) *
                Eigen::AngleAxisd(v[5], Eigen::Vector3d::UnitX()))
                   .toRotationMatrix();
  return T;
}

}  // namespace

MappingNodeOptions mappingNodeOptionsFromParams(const ros::NodeHandle& pnh) {
  MappingNodeOptions o;
  o.config = configFromParams(pnh, "config");
  readParam(pnh, "map_frame", &o.map_frame);
  o.map_frame = frameParam(o.map_frame);
  o.world_frame = o.map_frame;
  readParam(pnh, "world_frame", &o.world_frame);
  o.world_frame = frameParam(o.world_frame);
  readParam(pnh, "odom_frame", &o.odom_frame);
  o.odom_frame = frameParam(o.odom_frame);
  readParam(pnh, "camera_frame", &o.camera_frame);
  o.camera_frame = frameParam(o.camera_frame);
  std::vector<double> world_in_map;
  if (pnh.getParam("world_in_map", world_in_map) && !world_in_map.empty() && o.odom_frame.empty() &&
      o.world_frame != o.map_frame) {
    if (world_in_map.size() != 6) badParam("world_in_map", "needs 6 numbers: x y z yaw pitch roll");
    o.world_in_map = fromXyzYawPitchRoll(world_in_map);
  }
  readParam(pnh, "map", &o.map);
  readPeriod(pnh, "dense_publish_period", &o.dense_publish_period);
  readPeriod(pnh, "grid_publish_period", &o.grid_publish_period);
  readParam(pnh, "keyframe_topic", &o.keyframe_topic);
  readParam(pnh, "pose_topic", &o.pose_topic);
  readParam(pnh, "map_update_topic", &o.map_update_topic);
  readParam(pnh, "map_snapshot_topic", &o.map_snapshot_topic);
  readParam(pnh, "resend_service", &o.resend_service);
  readParam(pnh, "tracker_save_map_service", &o.tracker_save_map_service);
  readParam(pnh, "map_keyframes", &o.map_keyframes);
  readParam(pnh, "hand_over_service", &o.hand_over_service);
  readParam(pnh, "mapping_job_topic", &o.mapping_job_topic);
  readParam(pnh, "updates_wanted_topic", &o.updates_wanted_topic);
  // Said at the start, as the tracker says it: the mapping side apart loads the map file.
  const std::filesystem::path map_file = std::filesystem::path(o.map) / System::kMapFileName;
  if (o.map_keyframes && !o.map.empty() && !std::filesystem::is_regular_file(map_file))
    badParam("map", "has no map file " + map_file.string());
  return o;
}

}  // namespace ply_slam
