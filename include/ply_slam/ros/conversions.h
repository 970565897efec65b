#pragma once

// The one place that knows both worlds (DESIGN.md): library structs <-> ROS messages, 1:1.
#include <geometry_msgs/Pose.h>
#include <ply_slam/KeyFrameMsg.h>
#include <ply_slam/MapSnapshotMsg.h>
#include <ply_slam/MapUpdateMsg.h>

#include <Eigen/Geometry>
#include <string>

#include "ply_slam/common/stamped_pose.h"
#include "ply_slam/map/key_frame_packet.h"

namespace ply_slam {

geometry_msgs::Pose toPoseMsg(const Eigen::Isometry3d& T);
// Throws std::invalid_argument when the quaternion is not finite or near zero length.
Eigen::Isometry3d fromPoseMsg(const geometry_msgs::Pose& pose);

// `world_frame` goes into header.frame_id.
KeyFrameMsg toMsg(const KeyFramePacket& packet, const std::string& world_frame);
// Throws std::invalid_argument on an inconsistent message (descriptor rows vs keypoints,
// image encodings other than the ones toMsg writes).
KeyFramePacket fromMsg(const KeyFrameMsg& msg);

MapUpdateMsg toMsg(const MapUpdate& update, const std::string& world_frame);
MapUpdate fromMsg(const MapUpdateMsg& msg);

// A MapSnapshotMsg's keyframes (images empty) and tracked poses (camera -> world, in time order).
struct MapSnapshot {
  std::vector<KeyFramePacket> keyframes;
  Trajectory trajectory;
};
// Throws std::invalid_argument as the keyframe and pose conversions do.
MapSnapshot fromMsg(const MapSnapshotMsg& msg);

}  // namespace ply_slam
