// mapping_node's copy of the map (MapStore) and configs from YAML text (what the nodes build
// from rosparam).
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "ply_slam/io/tum_trajectory_file.h"
#include "ply_slam/map/map.h"
#include "ply_slam/map/map_store.h"
#include "ply_slam/system/system_config.h"

namespace ply_slam {
namespace {

KeyFramePacket packet(long id, double stamp, double x) {
  KeyFramePacket p;
  p.id = id;
  p.stamp = stamp;
  p.T_wc.translation() = Eigen::Vector3d(x, 0, 0);
  p.points = {{10 * id, {x, 1, 2}}, {10 * id + 1, {x, 2, 3}}};
  p.lines = {{id, {0, 0, x}, {1, 0, x}}};
  p.rgb = cv::Mat::zeros(4, 4, CV_8UC3);
  p.instances = {{1, "person", 0.9f, true}};
  return p;
}

std::string readAll(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(MapStore, KeepsKeyFramesAndLandmarksWithoutImages) {
  MapStore store;
  EXPECT_TRUE(store.insert(packet(0, 1.0, 0.0)));
  EXPECT_TRUE(store.insert(packet(1, 2.0, 1.0)));
  EXPECT_EQ(store.keyFrames().size(), 2u);
  EXPECT_EQ(store.points().size(), 4u);
  EXPECT_EQ(store.lines().size(), 2u);
  EXPECT_TRUE(store.keyFrames().at(1).rgb.empty());
  EXPECT_EQ(store.keyFrames().at(1).instances.size(), 1u);
  // A packet older than the one stored under its id is refused.
  EXPECT_FALSE(store.insert(packet(1, 1.5, 9.0)));
  EXPECT_EQ(store.keyFrames().at(1).T_wc.translation().x(), 1.0);
  // A newer position of a landmark replaces the old one.
  KeyFramePacket again = packet(2, 3.0, 2.0);
  again.points.push_back({0, {7, 7, 7}});
  store.insert(again);
  EXPECT_EQ(store.points().at(0).position, Eigen::Vector3d(7, 7, 7));
}

TEST(MapStore, AppliesUpdates) {
  MapStore store;
  store.insert(packet(0, 1.0, 0.0));
  store.insert(packet(1, 2.0, 1.0));
  MapUpdate update;
  Eigen::Isometry3d moved = Eigen::Isometry3d::Identity();
  moved.translation() = Eigen::Vector3d(0, 5, 0);
  update.keyframes = {{1, moved.inverse()}, {99, moved.inverse()}};  // 99 is unknown: ignored
  update.points = {{11, {3, 3, 3}}};
  update.erased_points = {10};  // merged into 11
  store.insert(packet(2, 3.0, 2.0));
  update.erased_keyframes = {2, 98};  // 98 is unknown: ignored
  store.apply(update);
  EXPECT_EQ(store.keyFrames().count(2), 0u);
  EXPECT_EQ(store.keyFrames().size(), 2u);
  EXPECT_EQ(store.keyFrames().at(1).T_wc.translation(), Eigen::Vector3d(0, 5, 0));
  EXPECT_EQ(store.keyFrames().count(99), 0u);
  EXPECT_EQ(store.points().at(11).position, Eigen::Vector3d(3, 3, 3));
  EXPECT_EQ(store.points().count(10), 0u);
}

TEST(MapStore, ForgetsErasedPoints) {
  MapStore store;
  store.insert(packet(0, 1.0, 0.0));
  store.insert(packet(1, 2.0, 1.0));
  MapUpdate update;
  update.erased_points = {1, 10, 77};  // 77 is unknown: ignored
  store.apply(update);
  ASSERT_EQ(store.points().size(), 2u);
  EXPECT_EQ(store.points().count(0), 1u);
  EXPECT_EQ(store.points().count(11), 1u);
}

TEST(MapStore, ForgetsErasedLines) {
  MapStore store;
  store.insert(packet(0, 1.0, 0.0));
  store.insert(packet(1, 2.0, 1.0));
  MapUpdate update;
  update.erased_lines = {0, 55};  // 55 is unknown: ignored
  store.apply(update);
  ASSERT_EQ(store.lines().size(), 1u);
  EXPECT_EQ(store.lines().count(1), 1u);
}

TEST(MapStore, SavesEverythingItHolds) {
  MapStore store;
  store.insert(packet(0, 1.0, 0.0));
  store.insert(packet(1, 2.0, 1.0));
  const auto dir = std::filesystem::temp_directory_path() /
                   ("ply_slam_map_store_test_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  store.save(dir.string());
  const Trajectory keyframes = readTumTrajectory((dir / "KeyFrameTrajectory.txt").string());
  ASSERT_EQ(keyframes.size(), 2u);
  EXPECT_EQ(keyframes[1].T_wc.translation().x(), 1.0);
  EXPECT_NE(readAll(dir / "map_points.ply").find("element vertex 4"), std::string::npos);
  EXPECT_NE(readAll(dir / "map_lines.ply").find("element edge 2"), std::string::npos);
  EXPECT_NE(readAll(dir / "keyframes.csv").find("person(dynamic)"), std::string::npos);
  std::filesystem::remove_all(dir);
  EXPECT_THROW(store.save("/proc/ply_slam_cannot_write_here"), std::exception);
}

// save_map's answer: a file that cannot be written is named, the others are still written.
TEST(MapStore, NamesAFileItCannotWriteAndWritesTheOthers) {
  MapStore store;
  store.insert(packet(0, 1.0, 0.0));
  const auto dir = std::filesystem::temp_directory_path() /
                   ("ply_slam_map_store_fail_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir / "map_points.ply");
  try {
    store.save(dir.string());
    ADD_FAILURE() << "a folder in place of map_points.ply went unnoticed";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find((dir / "map_points.ply").string()), std::string::npos)
        << e.what();
  }
  for (const char* name : {"KeyFrameTrajectory.txt", "map_lines.ply", "keyframes.csv"})
    EXPECT_TRUE(std::filesystem::is_regular_file(dir / name)) << name;
  std::filesystem::remove_all(dir);
}

TEST(ConfigFromString, SameChecksAsFiles) {
  const std::string path = std::string(PLY_SLAM_SOURCE_DIR) + "/config/tum_fr1.yaml";
  const SystemConfig from_file = loadConfig(path);
  const SystemConfig from_text = loadConfigFromString(readAll(path), "parameter /x/config");
  EXPECT_EQ(from_text.camera.fx, from_file.camera.fx);
  EXPECT_EQ(from_text.tracking.keyframe_max_frames, from_file.tracking.keyframe_max_frames);
  EXPECT_EQ(from_text.source_path, "parameter /x/config");
  try {
    loadConfigFromString(
        "camera: {fx: 1, fy: 1, cx: 1, cy: 1, width: 2, height: 2}\norb: {nfeat: 3}",
        "parameter /x/config");
    FAIL() << "an unknown key must be refused";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("parameter /x/config: orb.nfeat"), std::string::npos)
        << e.what();
  }
  EXPECT_THROW(loadConfigFromString("camera: [", "parameter /x/config"), ConfigError);
}

}  // namespace
}  // namespace ply_slam
