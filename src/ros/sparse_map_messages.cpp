#include "ply_slam/ros/sparse_map_messages.h"

#include <sensor_msgs/point_cloud2_iterator.h>

#include "ply_slam/ros/conversions.h"

namespace ply_slam {

sensor_msgs::PointCloud2 toMapPointsMsg(const std::map<long, LandmarkPoint>& points,
                                        const std_msgs::Header& header) {
  sensor_msgs::PointCloud2 cloud;
  cloud.header = header;
  sensor_msgs::PointCloud2Modifier modifier(cloud);
  modifier.setPointCloud2FieldsByString(1, "xyz");
  modifier.resize(points.size());
  if (points.empty()) return cloud;  // an iterator over no data dereferences a null pointer
  sensor_msgs::PointCloud2Iterator<float> x(cloud, "x"), y(cloud, "y"), z(cloud, "z");
  for (const auto& [id, p] : points) {
    *x = static_cast<float>(p.position.x());
    *y = static_cast<float>(p.position.y());
    *z = static_cast<float>(p.position.z());
    ++x, ++y, ++z;
  }
  return cloud;
}

visualization_msgs::MarkerArray toMapLinesMsg(const std::map<long, LandmarkLine>& lines,
                                              const std_msgs::Header& header) {
  visualization_msgs::Marker marker;
  marker.header = header;
  marker.ns = "map_lines";
  marker.type = visualization_msgs::Marker::LINE_LIST;
  marker.action = visualization_msgs::Marker::ADD;
  marker.pose.orientation.w = 1.0;
  marker.scale.x = 0.01;
  marker.color.r = 0.1f;
  marker.color.g = 0.6f;
  marker.color.b = 1.0f;
  marker.color.a = 1.0f;
  for (const auto& [id, l] : lines) {
    geometry_msgs::Point a, b;
    a.x = l.start.x(), a.y = l.start.y(), a.z = l.start.z();
    b.x = l.end.x(), b.y = l.end.y(), b.z = l.end.z();
    marker.points.push_back(a);
    marker.points.push_back(b);
  }
  if (marker.points.empty()) marker.action = visualization_msgs::Marker::DELETEALL;
  visualization_msgs::MarkerArray markers;
  markers.markers.push_back(marker);
  return markers;
}

geometry_msgs::PoseArray toKeyFramePosesMsg(const std::map<long, KeyFramePacket>& keyframes,
                                            const std_msgs::Header& header) {
  geometry_msgs::PoseArray poses;
  poses.header = header;
  for (const auto& [id, kf] : keyframes) poses.poses.push_back(toPoseMsg(kf.T_wc));
  return poses;
}

nav_msgs::Path toKeyFramePathMsg(const std::map<long, KeyFramePacket>& keyframes,
                                 const std_msgs::Header& header) {
  nav_msgs::Path path;
  path.header = header;
  for (const auto& [id, kf] : keyframes) {
    geometry_msgs::PoseStamped pose;
    pose.header.frame_id = header.frame_id;
    pose.header.stamp.fromSec(kf.stamp);
    pose.pose = toPoseMsg(kf.T_wc);
    path.poses.push_back(pose);
  }
  return path;
}

}  // namespace ply_slam
