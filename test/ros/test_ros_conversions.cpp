// Round trips of the tracker <-> mapper structs through their ROS messages, serialised as on
// the wire: every field must come back as it went.
#include <gtest/gtest.h>
#include <ros/serialization.h>

#include <cmath>
#include <limits>

#include "ply_slam/ros/conversions.h"
#include "ply_slam/ros/grid_map_message.h"
#include "wire_test_helpers.h"

namespace ply_slam {
namespace {

using test::expectRejectedNaming;
using test::sameImage;
using test::throughWire;

Eigen::Isometry3d somePose(double a) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(a, Eigen::Vector3d(1, -2, 0.5).normalized()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(a, -2 * a, 0.3);
  return T;
}

void expectSamePose(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  EXPECT_LT((a.matrix() - b.matrix()).cwiseAbs().maxCoeff(), 1e-12);
}

KeyFramePacket fullPacket() {
  KeyFramePacket p;
  p.id = 7;
  p.frame_id = 42;
  p.stamp = 1305031234.529645;
  p.T_wc = somePose(0.7);
  p.camera.fx = 517.3, p.camera.fy = 516.5, p.camera.cx = 318.6, p.camera.cy = 255.3;
  p.camera.width = 64, p.camera.height = 48;
  p.camera.distortion = (cv::Mat_<double>(1, 5) << 0.26, -0.95, -0.005, 0.002, 1.16);
  p.camera.depth_factor = 5000, p.camera.min_depth = 0.3, p.camera.max_depth = 6;
  p.camera.depth_noise = {2.5e-5, 1e-6, 1e-5, 2.5e-5};
  p.camera.rolling_shutter_readout = 0.02;
  cv::RNG rng(3);
  p.descriptors = cv::Mat(5, 32, CV_8U);
  rng.fill(p.descriptors, cv::RNG::UNIFORM, 0, 256);
  for (int i = 0; i < 5; ++i) {
    p.keypoints.emplace_back(10.25 * i, 3.5 + i);
    p.keypoint_depth.push_back(i == 2 ? 0.f : 0.5f + i);
    p.keypoint_level.push_back(i % 3);
    p.keypoint_landmark.push_back(i == 1 ? -1 : 100 + i);
  }
  p.points = {{100, {1, 2, 3}}, {103, {-1, 0.5, 2.25}}};
  p.lines = {{9, {0, 0, 1}, {1, 0, 1}}};
  p.rgb = cv::Mat(48, 64, CV_8UC3);
  rng.fill(p.rgb, cv::RNG::UNIFORM, 0, 256);
  p.depth = cv::Mat(48, 64, CV_32F);
  rng.fill(p.depth, cv::RNG::UNIFORM, 0.0, 5.0);
  p.label_image = cv::Mat::zeros(48, 64, CV_16U);
  p.label_image(cv::Rect(5, 5, 10, 10)) = 3;
  p.instances = {{3, "person", 0.9f, true}, {4, "chair", 0.6f, false}};
  p.dynamic_mask = cv::Mat::zeros(48, 64, CV_8U);
  p.dynamic_mask(cv::Rect(4, 4, 12, 12)) = 255;
  return p;
}

TEST(RosConversions, KeyFramePacketRoundTrip) {
  const KeyFramePacket p = fullPacket();
  const KeyFrameMsg msg = throughWire(toMsg(p, "map"));
  EXPECT_EQ(msg.header.frame_id, "map");
  const KeyFramePacket q = fromMsg(msg);
  EXPECT_EQ(q.id, p.id);
  EXPECT_EQ(q.frame_id, p.frame_id);
  EXPECT_EQ(q.stamp, p.stamp);
  expectSamePose(q.T_wc, p.T_wc);
  EXPECT_EQ(q.camera.fx, p.camera.fx);
  EXPECT_EQ(q.camera.cy, p.camera.cy);
  EXPECT_EQ(q.camera.width, p.camera.width);
  EXPECT_TRUE(sameImage(q.camera.distortion, p.camera.distortion));
  EXPECT_EQ(q.camera.depth_noise.beta, p.camera.depth_noise.beta);
  EXPECT_EQ(q.camera.depth_noise.delta, p.camera.depth_noise.delta);
  EXPECT_EQ(q.camera.rolling_shutter_readout, p.camera.rolling_shutter_readout);
  EXPECT_EQ(q.camera.max_depth, p.camera.max_depth);
  EXPECT_EQ(q.keypoints, p.keypoints);
  EXPECT_EQ(q.keypoint_depth, p.keypoint_depth);
  EXPECT_EQ(q.keypoint_level, p.keypoint_level);
  EXPECT_EQ(q.keypoint_landmark, p.keypoint_landmark);
  EXPECT_TRUE(sameImage(q.descriptors, p.descriptors));
  ASSERT_EQ(q.points.size(), 2u);
  EXPECT_EQ(q.points[1].id, 103);
  EXPECT_EQ(q.points[1].position, p.points[1].position);
  ASSERT_EQ(q.lines.size(), 1u);
  EXPECT_EQ(q.lines[0].end, p.lines[0].end);
  EXPECT_TRUE(sameImage(q.rgb, p.rgb));
  EXPECT_TRUE(sameImage(q.depth, p.depth));
  EXPECT_TRUE(sameImage(q.label_image, p.label_image));
  EXPECT_TRUE(sameImage(q.dynamic_mask, p.dynamic_mask));
  ASSERT_EQ(q.instances.size(), 2u);
  EXPECT_EQ(q.instances[0].class_name, "person");
  EXPECT_TRUE(q.instances[0].dynamic);
  EXPECT_FALSE(q.instances[1].dynamic);
  EXPECT_EQ(q.instances[1].score, 0.6f);
}

TEST(RosConversions, EmptyImagesStayEmpty) {
  KeyFramePacket p = fullPacket();
  p.label_image.release();
  p.dynamic_mask.release();
  p.instances.clear();
  const KeyFramePacket q = fromMsg(throughWire(toMsg(p, "map")));
  EXPECT_TRUE(q.label_image.empty());
  EXPECT_TRUE(q.dynamic_mask.empty());
  EXPECT_TRUE(q.instances.empty());
}

TEST(RosConversions, InconsistentKeyFrameIsRejected) {
  KeyFrameMsg msg = toMsg(fullPacket(), "map");
  msg.descriptors.pop_back();
  EXPECT_THROW(fromMsg(msg), std::invalid_argument);
  msg = toMsg(fullPacket(), "map");
  msg.T_wc.orientation.w = msg.T_wc.orientation.x = msg.T_wc.orientation.y =
      msg.T_wc.orientation.z = 0;
  EXPECT_THROW(fromMsg(msg), std::invalid_argument);
  msg = toMsg(fullPacket(), "map");
  msg.depth.encoding = "16UC1";
  EXPECT_THROW(fromMsg(msg), std::invalid_argument);
}

// A NaN or absurd number in a message must not reach the map: it is refused with the field.
TEST(RosConversions, NotFiniteNumbersAreRejected) {
  KeyFrameMsg msg = toMsg(fullPacket(), "map");
  msg.camera.distortion[0] = std::nan("");
  expectRejectedNaming([&] { fromMsg(msg); }, "distortion");
  msg = toMsg(fullPacket(), "map");
  msg.camera.fx = 1e-300;
  expectRejectedNaming([&] { fromMsg(msg); }, "fx");
  msg = toMsg(fullPacket(), "map");
  msg.camera.depth_noise_alpha = std::nan("");
  expectRejectedNaming([&] { fromMsg(msg); }, "depth_noise.alpha");
  msg = toMsg(fullPacket(), "map");
  msg.T_wc.position.y = std::numeric_limits<double>::infinity();
  EXPECT_THROW(fromMsg(msg), std::invalid_argument);
  msg = toMsg(fullPacket(), "map");
  msg.points[1].position.z = std::nan("");
  EXPECT_THROW(fromMsg(msg), std::invalid_argument);
  MapUpdate u;
  u.points = {{11, {0.1, std::nan(""), 0.3}}};
  EXPECT_THROW(fromMsg(toMsg(u, "map")), std::invalid_argument);
}

sensor_msgs::CameraInfo someCameraInfo() {
  sensor_msgs::CameraInfo info;
  info.width = 640;
  info.height = 480;
  info.K = {517.3, 0, 318.6, 0, 516.5, 255.3, 0, 0, 1};
  info.D = {0.26, -0.95, -0.005, 0.002, 1.16};
  return info;
}

TEST(RosConversions, CameraInfoIsCheckedLikeTheConfig) {
  const PinholeCamera camera = cameraFromInfo(someCameraInfo(), PinholeCamera());
  EXPECT_EQ(camera.fx, 517.3);
  EXPECT_EQ(camera.cy, 255.3);
  EXPECT_EQ(camera.width, 640);
  EXPECT_EQ(camera.distortion.at<double>(0, 4), 1.16);
  sensor_msgs::CameraInfo info = someCameraInfo();
  info.D[1] = std::nan("");
  expectRejectedNaming([&] { cameraFromInfo(info, PinholeCamera()); }, "distortion");
  info = someCameraInfo();
  info.K[4] = std::numeric_limits<double>::infinity();
  expectRejectedNaming([&] { cameraFromInfo(info, PinholeCamera()); }, "fy");
  info = someCameraInfo();
  info.width = 0;
  expectRejectedNaming([&] { cameraFromInfo(info, PinholeCamera()); }, "width");
}

// A job's camera: the mapping side apart maps in it when it is not its config's (sameCamera).
TEST(RosConversions, CameraRoundTripAndComparison) {
  const PinholeCamera camera = cameraFromInfo(someCameraInfo(), PinholeCamera());
  const PinholeCamera back = fromMsg(toMsg(camera));
  EXPECT_TRUE(sameCamera(camera, back));
  PinholeCamera other = back;
  other.cx += 1e-9;
  EXPECT_FALSE(sameCamera(camera, other));
  other = back;
  other.depth_noise.alpha *= 2;
  EXPECT_FALSE(sameCamera(camera, other));
  other = back;
  other.distortion = cv::Mat();  // none
  EXPECT_FALSE(sameCamera(camera, other));
  PinholeCamera rectified = back;
  rectified.distortion = cv::Mat::zeros(1, 5, CV_64F);
  other.distortion = cv::Mat();  // all zero and none: the same
  EXPECT_TRUE(sameCamera(rectified, other));
  CameraMsg bad = toMsg(camera);
  bad.fx = std::nan("");
  EXPECT_THROW(fromMsg(bad), std::invalid_argument);
}

// Bit for bit: a copy of the map that tracks gets the mapping side's doubles (MapUpdate).
TEST(RosConversions, MapUpdateRoundTrip) {
  MapUpdate u;
  u.stamp = 12.5;
  u.keyframes = {{1, somePose(0.1), -1}, {4, somePose(-2.0), 1}};
  u.points = {{11, {0.1, 0.2, 0.3}, Eigen::Vector3d(1, 2, 3).normalized(), 1.0 / 3.0}};
  u.lines = {{5, {1, 1, 1}, {2, 2, 2.0 / 7.0}, 0.1, 1e-9}};
  u.erased_keyframes = {2, 3};
  u.erased_points = {7, 8, 9};
  u.erased_lines = {4, 5};
  u.whole_map = true;
  u.replayed = {4, {{0, 11}, {17, 12}}};
  using C = MapJournal::Change;
  u.journal.entries = {{C::kAddObservation, 4, 11, -1, 17, 0},
                       {C::kRemoveObservation, 1, -1, -1, 3, 0},
                       {C::kReplace, -1, 9, 11, 0, 0},
                       {C::kErasePoint, -1, 8, -1, 0, 0},
                       {C::kEraseKeyFrame, 2, -1, -1, 0, 3}};
  u.world_corrections = {somePose(0.01), somePose(-0.3)};
  const MapUpdate v = fromMsg(throughWire(toMsg(u, "map")));
  EXPECT_EQ(v.stamp, u.stamp);
  ASSERT_EQ(v.keyframes.size(), 2u);
  for (size_t k = 0; k < 2; ++k) {
    EXPECT_EQ(v.keyframes[k].id, u.keyframes[k].id);
    EXPECT_TRUE(v.keyframes[k].T_cw.matrix() == u.keyframes[k].T_cw.matrix());
    EXPECT_EQ(v.keyframes[k].parent, u.keyframes[k].parent);
  }
  ASSERT_EQ(v.points.size(), 1u);
  EXPECT_EQ(v.points[0].position, u.points[0].position);
  EXPECT_EQ(v.points[0].normal, u.points[0].normal);
  EXPECT_EQ(v.points[0].position_weight, u.points[0].position_weight);
  ASSERT_EQ(v.lines.size(), 1u);
  EXPECT_EQ(v.lines[0].start, u.lines[0].start);
  EXPECT_EQ(v.lines[0].end, u.lines[0].end);
  EXPECT_EQ(v.lines[0].start_weight, u.lines[0].start_weight);
  EXPECT_EQ(v.lines[0].end_weight, u.lines[0].end_weight);
  EXPECT_EQ(v.erased_keyframes, (std::vector<long>{2, 3}));
  EXPECT_EQ(v.erased_points, (std::vector<long>{7, 8, 9}));
  EXPECT_EQ(v.erased_lines, (std::vector<long>{4, 5}));
  EXPECT_TRUE(v.whole_map);
  EXPECT_EQ(v.replayed.keyframe, 4);
  EXPECT_EQ(v.replayed.points, u.replayed.points);
  ASSERT_EQ(v.journal.entries.size(), u.journal.entries.size());
  for (size_t i = 0; i < u.journal.entries.size(); ++i) {
    const auto &a = v.journal.entries[i], &b = u.journal.entries[i];
    EXPECT_TRUE(a.change == b.change && a.keyframe == b.keyframe && a.point == b.point &&
                a.winner == b.winner && a.index == b.index &&
                a.min_point_observers == b.min_point_observers)
        << "journal entry " << i;
  }
  ASSERT_EQ(v.world_corrections.size(), 2u);
  for (size_t i = 0; i < 2; ++i)
    EXPECT_TRUE(v.world_corrections[i].matrix() == u.world_corrections[i].matrix());
}

TEST(RosConversions, MapUpdateWithABadPoseOrChangeIsRejected) {
  MapUpdate u;
  u.keyframes = {{1, somePose(0.1), -1}};
  MapUpdateMsg msg = toMsg(u, "map");
  msg.keyframes[0].T_cw.matrix[0] = 2.0;  // a scaled rotation
  expectRejectedNaming([&] { fromMsg(msg); }, "rotation");
  msg = toMsg(u, "map");
  msg.keyframes[0].T_cw.matrix[3] = std::nan("");
  expectRejectedNaming([&] { fromMsg(msg); }, "not finite");
  msg = toMsg(u, "map");
  msg.journal.resize(1);
  msg.journal[0].change = 9;
  expectRejectedNaming([&] { fromMsg(msg); }, "unknown change");
  msg = toMsg(u, "map");
  msg.replayed_points = {3};
  expectRejectedNaming([&] { fromMsg(msg); }, "replayed keypoints");
}

// The grid message: cells as stored, and info.origin the pose of cell (0, 0)'s corner in the
// message's frame.
TEST(RosConversions, OccupancyGridMessage) {
  FloorFrame floor;
  floor.T_world_floor = somePose(0.4);
  OccupancyGrid grid(3, 2, 0.05, Eigen::Vector2d(-0.5, 0.25), floor);
  grid.set(2, 0, OccupancyGrid::kOccupied);
  grid.set(0, 1, OccupancyGrid::kFree);
  std_msgs::Header header;
  header.frame_id = "map";
  const Eigen::Isometry3d T_map_floor = somePose(0.9);
  const nav_msgs::OccupancyGrid msg = throughWire(toGridMsg(grid, T_map_floor, header));
  EXPECT_EQ(msg.header.frame_id, "map");
  EXPECT_EQ(msg.info.width, 3u);
  EXPECT_EQ(msg.info.height, 2u);
  EXPECT_FLOAT_EQ(msg.info.resolution, 0.05f);
  EXPECT_EQ(msg.data, (std::vector<std::int8_t>{-1, -1, 100, 0, -1, -1}));
  Eigen::Isometry3d corner = T_map_floor;
  corner.translation() = T_map_floor * Eigen::Vector3d(-0.5, 0.25, 0.0);
  expectSamePose(fromPoseMsg(msg.info.origin), corner);
}

// tf: T maps the child's coordinates into the parent's; the frames and stamp as given.
TEST(RosConversions, TransformRoundTrip) {
  const Eigen::Isometry3d T = somePose(0.7);
  const geometry_msgs::TransformStamped t =
      throughWire(toTransformMsg(T, ros::Time(12.5), "map", "odom"));
  EXPECT_EQ(t.header.frame_id, "map");
  EXPECT_EQ(t.child_frame_id, "odom");
  EXPECT_EQ(t.header.stamp, ros::Time(12.5));
  EXPECT_DOUBLE_EQ(t.transform.translation.x, T.translation().x());
  expectSamePose(fromTransformMsg(t.transform), T);
  geometry_msgs::Transform zero = t.transform;
  zero.rotation.w = zero.rotation.x = zero.rotation.y = zero.rotation.z = 0.0;
  EXPECT_THROW(fromTransformMsg(zero), std::invalid_argument);
}

}  // namespace
}  // namespace ply_slam
