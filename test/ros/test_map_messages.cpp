// The map display messages mapping_node publishes: the points, the dense cloud and the octree
// voxels carry every value in their fields, and an empty map gives an empty, valid cloud (the
// sanitized rostests found the field iterators dereferencing a null pointer on an empty map).
#include <gtest/gtest.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <sensor_msgs/point_cloud2_iterator.h>

#include "ply_slam/ros/dense_map_messages.h"
#include "ply_slam/ros/sparse_map_messages.h"

namespace ply_slam {
namespace {

std_msgs::Header mapHeader() {
  std_msgs::Header header;
  header.frame_id = "map";
  header.stamp.fromSec(12.5);
  return header;
}

void expectEmptyCloud(const sensor_msgs::PointCloud2& msg, size_t fields) {
  EXPECT_EQ(msg.width * msg.height, 0u);
  EXPECT_TRUE(msg.data.empty());
  EXPECT_EQ(msg.fields.size(), fields);
  EXPECT_EQ(msg.header.frame_id, "map");
}

TEST(MapMessages, EmptyMapsGiveEmptyClouds) {
  expectEmptyCloud(toMapPointsMsg({}, mapHeader()), 3);
  expectEmptyCloud(toDenseCloudMsg(DenseCloud(), mapHeader()), 5);
  expectEmptyCloud(toVoxelCloudMsg({}, mapHeader()), 4);
}

TEST(MapMessages, PointsKeepTheirPositions) {
  std::map<long, LandmarkPoint> points;
  points[4] = {4, Eigen::Vector3d(1.0, -2.0, 0.25)};
  points[9] = {9, Eigen::Vector3d(-0.5, 3.0, 7.0)};
  const auto msg = toMapPointsMsg(points, mapHeader());
  ASSERT_EQ(msg.width * msg.height, 2u);
  sensor_msgs::PointCloud2ConstIterator<float> x(msg, "x"), y(msg, "y"), z(msg, "z");
  for (const auto& [id, p] : points) {
    EXPECT_FLOAT_EQ(*x, p.position.x());
    EXPECT_FLOAT_EQ(*y, p.position.y());
    EXPECT_FLOAT_EQ(*z, p.position.z());
    ++x, ++y, ++z;
  }
}

TEST(MapMessages, DenseCloudKeepsColourAndLabel) {
  DenseCloud cloud;
  pcl::PointXYZRGBL p;
  p.x = 1.f, p.y = 2.f, p.z = 3.f, p.r = 200, p.g = 100, p.b = 50, p.label = 57;
  cloud.push_back(p);
  const auto msg = toDenseCloudMsg(cloud, mapHeader());
  ASSERT_EQ(msg.width * msg.height, 1u);
  sensor_msgs::PointCloud2ConstIterator<float> z(msg, "z");
  sensor_msgs::PointCloud2ConstIterator<uint8_t> rgb(msg, "rgb");  // bytes b g r a
  sensor_msgs::PointCloud2ConstIterator<uint32_t> label(msg, "label");
  EXPECT_FLOAT_EQ(*z, 3.f);
  EXPECT_EQ(rgb[0], 50);
  EXPECT_EQ(rgb[1], 100);
  EXPECT_EQ(rgb[2], 200);
  EXPECT_EQ(*label, 57u);
}

TEST(MapMessages, VoxelCloudHoldsTheCentres) {
  SemanticOctree::Voxel v;
  v.centre = Eigen::Vector3d(0.025, -0.075, 1.125);
  v.size = 0.05;
  v.colour.r = 10, v.colour.g = 20, v.colour.b = 30;
  const auto msg = toVoxelCloudMsg({v, v}, mapHeader());
  ASSERT_EQ(msg.width * msg.height, 2u);
  sensor_msgs::PointCloud2ConstIterator<float> x(msg, "x");
  sensor_msgs::PointCloud2ConstIterator<uint8_t> rgb(msg, "rgb");
  EXPECT_FLOAT_EQ(*x, 0.025f);
  EXPECT_EQ(rgb[2], 10);
}

}  // namespace
}  // namespace ply_slam
