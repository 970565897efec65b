#pragma once

#include <geometry_msgs/PoseArray.h>
#include <nav_msgs/Path.h>
#include <sensor_msgs/PointCloud2.h>
#include <std_msgs/Header.h>
#include <visualization_msgs/MarkerArray.h>

#include <map>

#include "ply_slam/map/key_frame_packet.h"

namespace ply_slam {

// The sparse map mapping_node keeps (MapStore) as ROS messages in header.frame_id: the points as
// a cloud with x y z; the lines as one LINE_LIST marker (DELETEALL while there are none, so rviz
// drops the old ones); the keyframes' camera poses as a PoseArray and as a path stamped with the
// keyframes' stamps.
sensor_msgs::PointCloud2 toMapPointsMsg(const std::map<long, LandmarkPoint>& points,
                                        const std_msgs::Header& header);
visualization_msgs::MarkerArray toMapLinesMsg(const std::map<long, LandmarkLine>& lines,
                                              const std_msgs::Header& header);
geometry_msgs::PoseArray toKeyFramePosesMsg(const std::map<long, KeyFramePacket>& keyframes,
                                            const std_msgs::Header& header);
nav_msgs::Path toKeyFramePathMsg(const std::map<long, KeyFramePacket>& keyframes,
                                 const std_msgs::Header& header);

}  // namespace ply_slam
