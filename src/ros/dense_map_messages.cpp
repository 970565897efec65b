#include "ply_slam/ros/dense_map_messages.h"

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <sensor_msgs/point_cloud2_iterator.h>

#include <map>

namespace ply_slam {
namespace {

using sensor_msgs::PointField;

// x y z as float32, rgb packed in a float32 (rviz's convention), and optionally a uint32 label.
void setFields(sensor_msgs::PointCloud2& msg, bool with_label, size_t n) {
  sensor_msgs::PointCloud2Modifier modifier(msg);
  if (with_label)
    modifier.setPointCloud2Fields(5, "x", 1, PointField::FLOAT32, "y", 1, PointField::FLOAT32, "z",
                                  1, PointField::FLOAT32, "rgb", 1, PointField::FLOAT32, "label", 1,
                                  PointField::UINT32);
  else
    modifier.setPointCloud2Fields(4, "x", 1, PointField::FLOAT32, "y", 1, PointField::FLOAT32, "z",
                                  1, PointField::FLOAT32, "rgb", 1, PointField::FLOAT32);
  modifier.resize(n);
}

}  // namespace

sensor_msgs::PointCloud2 toDenseCloudMsg(const DenseCloud& cloud, const std_msgs::Header& header) {
  sensor_msgs::PointCloud2 msg;
  msg.header = header;
  setFields(msg, true, cloud.size());
  if (cloud.empty()) return msg;  // an iterator over no data dereferences a null pointer
  sensor_msgs::PointCloud2Iterator<float> x(msg, "x"), y(msg, "y"), z(msg, "z");
  sensor_msgs::PointCloud2Iterator<uint8_t> rgb(msg, "rgb");  // bytes b g r a
  sensor_msgs::PointCloud2Iterator<uint32_t> label(msg, "label");
  for (const auto& p : cloud.points) {
    *x = p.x, *y = p.y, *z = p.z;
    rgb[0] = p.b, rgb[1] = p.g, rgb[2] = p.r, rgb[3] = 255;
    *label = p.label;
    ++x, ++y, ++z, ++rgb, ++label;
  }
  return msg;
}

visualization_msgs::MarkerArray toVoxelMarkers(const std::vector<SemanticOctree::Voxel>& voxels,
                                               const std_msgs::Header& header) {
  // One CUBE_LIST per colour and voxel size: rviz draws thousands of cubes in one marker.
  std::map<std::pair<uint32_t, double>, visualization_msgs::Marker> lists;
  for (const auto& v : voxels) {
    const uint32_t key = (uint32_t(v.colour.r) << 16) | (uint32_t(v.colour.g) << 8) | v.colour.b;
    auto [it, added] = lists.try_emplace({key, v.size});
    visualization_msgs::Marker& m = it->second;
    if (added) {
      m.header = header;
      m.ns = "octomap";
      m.type = visualization_msgs::Marker::CUBE_LIST;
      m.action = visualization_msgs::Marker::ADD;
      m.pose.orientation.w = 1.0;
      m.scale.x = m.scale.y = m.scale.z = v.size;
      m.color.r = v.colour.r / 255.f, m.color.g = v.colour.g / 255.f,
      m.color.b = v.colour.b / 255.f;
      m.color.a = 1.f;
    }
    geometry_msgs::Point p;
    p.x = v.centre.x(), p.y = v.centre.y(), p.z = v.centre.z();
    m.points.push_back(p);
  }
  visualization_msgs::MarkerArray array;
  visualization_msgs::Marker clear;  // drops the lists of colours that are gone
  clear.header = header;
  clear.ns = "octomap";
  clear.action = visualization_msgs::Marker::DELETEALL;
  array.markers.push_back(clear);
  int id = 0;
  for (auto& [key, m] : lists) {
    m.id = id++;
    array.markers.push_back(std::move(m));
  }
  return array;
}

sensor_msgs::PointCloud2 toVoxelCloudMsg(const std::vector<SemanticOctree::Voxel>& voxels,
                                         const std_msgs::Header& header) {
  sensor_msgs::PointCloud2 msg;
  msg.header = header;
  setFields(msg, false, voxels.size());
  if (voxels.empty()) return msg;
  sensor_msgs::PointCloud2Iterator<float> x(msg, "x"), y(msg, "y"), z(msg, "z");
  sensor_msgs::PointCloud2Iterator<uint8_t> rgb(msg, "rgb");
  for (const auto& v : voxels) {
    *x = static_cast<float>(v.centre.x()), *y = static_cast<float>(v.centre.y());
    *z = static_cast<float>(v.centre.z());
    rgb[0] = v.colour.b, rgb[1] = v.colour.g, rgb[2] = v.colour.r, rgb[3] = 255;
    ++x, ++y, ++z, ++rgb;
  }
  return msg;
}

}  // namespace ply_slam
