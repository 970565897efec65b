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

CameraMsg toMsg(const PinholeCamera& camera);
// Throws std::invalid_argument naming the field when a number is not finite or absurd.
PinholeCamera fromMsg(const CameraMsg& msg);
// The same intrinsics, image size, distortion, depth scale, range and noise, and readout.
bool sameCamera(const PinholeCamera& a, const PinholeCamera& b);
// "fx .. fy .. cx .. cy .., WxH", for logs and errors.
std::string intrinsicsText(const PinholeCamera& camera);

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
// Throws std::invalid_argument as the keyframe and pose conversions do, and as
// handoverFromFields.
MapSnapshot fromMsg(const MapSnapshotMsg& msg);
// The handover fields MapSnapshotMsg and MapForTracker's response share (map_file,
// updates_followed, loaded_map, next_*_id), written and read in one place.
template <class Fields>
void handoverToFields(const MapHandover& h, Fields& m) {
  m.map_file = h.map_file;
  m.updates_followed = h.updates_followed;
  m.loaded_map = h.loaded_map;
  m.next_keyframe_id = h.next_ids.keyframe;
  m.next_point_id = h.next_ids.point;
  m.next_line_id = h.next_ids.line;
}
// Throws std::invalid_argument naming a negative count or id.
void checkHandoverCounts(int64_t updates_followed, const Map::Ids& next_ids);
template <class Fields>
MapHandover handoverFromFields(const Fields& m) {
  const Map::Ids ids{m.next_keyframe_id, m.next_point_id, m.next_line_id};
  checkHandoverCounts(m.updates_followed, ids);
  return {m.map_file, m.updates_followed, m.loaded_map, ids};
}
// Header and poses in `world_frame`; the sequence numbers and the stamp are the sender's.
MapSnapshotMsg toMsg(const MapSnapshot& snapshot, const std::string& world_frame);

}  // namespace ply_slam
