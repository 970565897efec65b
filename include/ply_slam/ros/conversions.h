#pragma once

// The one place that knows both worlds (DESIGN.md): library structs <-> ROS messages, 1:1.
#include <geometry_msgs/Pose.h>
#include <geometry_msgs/TransformStamped.h>
#include <ply_slam/KeyFrameMsg.h>
#include <ply_slam/MapSnapshotMsg.h>
#include <ply_slam/MapUpdateMsg.h>
#include <sensor_msgs/CameraInfo.h>

#include <Eigen/Geometry>
#include <string>

#include "ply_slam/common/pinhole_camera.h"
#include "ply_slam/common/stamped_pose.h"
#include "ply_slam/map/key_frame_packet.h"
#include "ply_slam/system/mapping_job.h"

namespace ply_slam {

geometry_msgs::Pose toPoseMsg(const Eigen::Isometry3d& T);
// Throws std::invalid_argument when the quaternion is not finite or near zero length, or the
// position is not finite.
Eigen::Isometry3d fromPoseMsg(const geometry_msgs::Pose& pose);

// T as the tf from `parent` to `child` (T maps child coordinates into parent ones).
geometry_msgs::TransformStamped toTransformMsg(const Eigen::Isometry3d& T, const ros::Time& stamp,
                                               const std::string& parent, const std::string& child);
// Throws std::invalid_argument as fromPoseMsg does.
Eigen::Isometry3d fromTransformMsg(const geometry_msgs::Transform& transform);

// `base` with the intrinsics and size of a camera_info (plumb_bob / rational_polynomial: the
// first five coefficients are OpenCV's k1 k2 p1 p2 k3). Throws std::invalid_argument naming
// the field when a number is not finite or absurd (the checks of the config's camera).
PinholeCamera cameraFromInfo(const sensor_msgs::CameraInfo& info, PinholeCamera base);

// `world_frame` goes into header.frame_id.
KeyFrameMsg toMsg(const KeyFramePacket& packet, const std::string& world_frame);
// Throws std::invalid_argument on an inconsistent message (descriptor rows vs keypoints,
// image encodings other than the ones toMsg writes).
KeyFramePacket fromMsg(const KeyFrameMsg& msg);

MapUpdateMsg toMsg(const MapUpdate& update, const std::string& world_frame);
MapUpdate fromMsg(const MapUpdateMsg& msg);

// A MapSnapshotMsg's keyframes (images empty) and tracked poses (camera -> world, in time order),
// and with the mapping side apart the tracker's copy handed over (empty map_file: none).
struct MapSnapshot {
  std::vector<KeyFramePacket> keyframes;
  Trajectory trajectory;
  MapHandover handover;
};
// Throws std::invalid_argument as the keyframe and pose conversions do, and as handoverFromMsg.
MapSnapshot fromMsg(const MapSnapshotMsg& msg);
// A handover's fields from a message (MapSnapshotMsg, MapForTracker.srv); throws
// std::invalid_argument naming a negative count or id.
MapHandover handoverFromMsg(const std::vector<uint8_t>& map_file, int64_t updates_followed,
                            uint64_t loaded_map, const Map::Ids& next_ids);
// Header and poses in `world_frame`; the sequence numbers and the stamp are the sender's.
MapSnapshotMsg toMsg(const MapSnapshot& snapshot, const std::string& world_frame);

}  // namespace ply_slam
