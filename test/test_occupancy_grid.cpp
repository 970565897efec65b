// Dense module, occupancy grid: the floor found in a tilted world, moving classes never an
// obstacle, and map_server's files. (The synthetic office's grid against the scene's exact
// geometry: test_occupancy_grid_office.)
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <random>
#include <set>

#include "dense_test_scene.h"
#include "temp_dir.h"
#include "ply_slam/dense/floor_frame_estimator.h"
#include "ply_slam/dense/grid_map_files.h"
#include "ply_slam/dense/key_frame_cloud_builder.h"
#include "ply_slam/dense/occupancy_grid_builder.h"
#include "ply_slam/dense/semantic_octree.h"

namespace ply_slam {
namespace {

namespace fs = std::filesystem;
constexpr double kPi = 3.14159265358979323846;

// A world whose up is `up` (not an axis): a floor of 4 x 4 m at height h, a table top of
// 1 x 1 m 0.7 m above it and a wall; voxel centres of 5 cm, and cameras 1.4 m above the floor
// looking along the floor with their y axis down (tilted by `pitch` about their x axis).
struct TiltedRoom {
  Eigen::Vector3d up = Eigen::Vector3d(0.3, -0.9, 0.2).normalized();
  double floor_height = -1.3;
  Eigen::Vector3d e1, e2;
  std::vector<Eigen::Vector3d> points;
  Trajectory trajectory;

  explicit TiltedRoom(double pitch) {
    e1 = up.unitOrthogonal();
    e2 = up.cross(e1);
    auto at = [&](double x, double y, double z) {
      return Eigen::Vector3d(x * e1 + y * e2 + (floor_height + z) * up);
    };
    std::mt19937 rng(3);
    std::normal_distribution<double> noise(0.0, 0.01);
    for (double x = -2; x < 2; x += 0.05)
      for (double y = -2; y < 2; y += 0.05) points.push_back(at(x, y, noise(rng)));
    for (double x = 0.5; x < 1.5; x += 0.05)
      for (double y = 0.5; y < 1.5; y += 0.05) points.push_back(at(x, y, 0.7 + noise(rng)));
    for (double y = -2; y < 2; y += 0.05)
      for (double z = 0; z < 2.5; z += 0.05) points.push_back(at(2.0 + noise(rng), y, z));
    for (int k = 0; k < 5; ++k) {
      StampedPose pose;
      // Camera axes: x right (-e2), y down (-up), z forward (e1); then pitched.
      Eigen::Matrix3d R;
      R.col(0) = -e2;
      R.col(1) = -up;
      R.col(2) = e1;
      pose.T_wc.linear() =
          R * Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitX()).toRotationMatrix();
      pose.T_wc.translation() = at(-1.0 + 0.2 * k, 0.1 * k, 1.4);
      trajectory.push_back(pose);
    }
  }
};

TEST(FloorFrameEstimator, FindsATiltedFloorPlaneUnderAPitchedCamera) {
  for (double pitch_deg : {0.0, -20.0, 15.0}) {
    const TiltedRoom room(pitch_deg * kPi / 180.0);
    const FloorFrame floor =
        FloorFrameEstimator(OccupancyGridOptions()).estimate(room.points, 0.05, room.trajectory);
    EXPECT_EQ(floor.method, "plane") << pitch_deg;
    EXPECT_GE(floor.support, 6000u) << pitch_deg;  // the floor's 6400 points, not the table's
    const Eigen::Vector3d z = floor.T_world_floor.linear().col(2);
    EXPECT_LT(std::acos(std::min(1.0, z.dot(room.up))) * 180.0 / kPi, 0.5) << pitch_deg;
    EXPECT_NEAR(room.up.dot(floor.T_world_floor.translation()), room.floor_height, 0.01);
    // Origin under the first camera, x along its view on the floor.
    const Eigen::Vector3d c = room.trajectory[0].T_wc.translation();
    EXPECT_NEAR((floor.T_world_floor.inverse() * c).head<2>().norm(), 0.0, 0.01) << pitch_deg;
    EXPECT_GT(floor.T_world_floor.linear().col(0).dot(room.e1), 0.999) << pitch_deg;
  }
}

// A camera over a desk: 2 x 2 m of desk top 0.7 m up, but only 1.2 x 1.2 m of floor in view.
TEST(FloorFrameEstimator, TheFloorUnderALargerDeskTop) {
  TiltedRoom room(-20.0 * kPi / 180.0);
  std::vector<Eigen::Vector3d> points;
  for (double x = -1; x < 1; x += 0.05)
    for (double y = -1; y < 1; y += 0.05)
      points.push_back((room.floor_height + 0.7) * room.up + x * room.e1 + y * room.e2);
  for (double x = 1.2; x < 2.4; x += 0.05)
    for (double y = -0.6; y < 0.6; y += 0.05)
      points.push_back(room.floor_height * room.up + x * room.e1 + y * room.e2);
  const FloorFrame floor =
      FloorFrameEstimator(OccupancyGridOptions()).estimate(points, 0.05, room.trajectory);
  EXPECT_EQ(floor.method, "plane");
  EXPECT_NEAR(room.up.dot(floor.T_world_floor.translation()), room.floor_height, 0.01);
  EXPECT_GE(floor.support, 550u);  // the floor's 24 x 24 (or 25) points, not the desk's 1600
  EXPECT_LE(floor.support, 650u);
}

TEST(FloorFrameEstimator, GivenFloorAndFallbackWithoutAFloor) {
  OccupancyGridOptions given;
  given.floor = "given";
  given.up = Eigen::Vector3d(0, -1, 0);
  given.floor_height = -1.2;
  const TiltedRoom room(0.0);
  const FloorFrame floor = FloorFrameEstimator(given).estimate(room.points, 0.05, room.trajectory);
  EXPECT_EQ(floor.method, "given");
  EXPECT_TRUE(floor.T_world_floor.linear().col(2).isApprox(Eigen::Vector3d(0, -1, 0)));
  EXPECT_NEAR(-floor.T_world_floor.translation().y(), -1.2, 1e-12);
  // Only the wall: no plane near up below the cameras, so the lowest voxels make the floor.
  std::vector<Eigen::Vector3d> wall(room.points.end() - 80 * 50, room.points.end());
  const FloorFrame lowest =
      FloorFrameEstimator(OccupancyGridOptions()).estimate(wall, 0.05, room.trajectory);
  EXPECT_EQ(lowest.method, "lowest");
  EXPECT_NEAR(room.up.dot(lowest.T_world_floor.translation()), room.floor_height - 0.025, 0.03);
}

// A person standing in front of a wall, labelled but not marked moving: seen from three
// places, the octree keeps their voxels (occupied, class person). The grid leaves them out and
// still has the wall; the cells between camera and person, which rays passed, are free.
TEST(OccupancyGridBuilder, APersonTheOctreeKeepsOccupiesNoCell) {
  KeyFrameCloudBuilder cloud_builder(test::denseTestParams(1, 0.01), ClassPalette());
  SemanticOctree octree(0.05, SemanticOctree::ColourMode::kClass, ClassPalette(), 0.88, 0.1);
  Trajectory trajectory;
  for (int k = 0; k < 4; ++k) {
    const auto packet = test::wallPacket(k + 1, {0.02 * k, 0.0, 0.0}, true, false);
    octree.insert(cloud_builder.build(*packet));
    trajectory.push_back({double(k), packet->T_wc});
  }
  size_t person_voxels = 0;
  for (const auto& v : octree.occupiedVoxels()) person_voxels += v.label == 1;
  ASSERT_GT(person_voxels, 20u);

  // The camera (y down) 0.6 m above the floor: the person spans 0 to 1.06 m above it.
  OccupancyGridOptions options;
  options.floor = "given";
  options.up = Eigen::Vector3d(0, -1, 0);
  options.floor_height = -0.6;
  const FloorFrame floor = FloorFrameEstimator(options).estimate({}, 0.05, trajectory);
  // Floor frame: x along the view (world z), y to its left (world -x). The state of five cells
  // across at `left` +- 0.1 m, `forward` m ahead: all occupied, all free, or -2 (mixed).
  auto state = [](const OccupancyGrid& grid, double forward, double left) {
    int i = 0, j = 0, n[3] = {0, 0, 0};
    for (int k = -2; k <= 2; ++k)
      if (grid.cellOf({forward, left + 0.05 * k}, &i, &j)) {
        const std::int8_t s = grid.at(i, j);
        ++n[s == OccupancyGrid::kOccupied ? 0 : s == OccupancyGrid::kFree ? 1 : 2];
      }
    return n[0] == 5   ? OccupancyGrid::kOccupied
           : n[1] == 5 ? OccupancyGrid::kFree
                       : std::int8_t(-2);
  };
  // The person stands at left -0.15 to 0.23 m and hides the wall behind; the wall beside them.
  const double wall = test::kWallDepth, person = test::kWalkerDepth + 0.01, beside = 0.9;
  const OccupancyGridBuilder builder(options,
                                     OccupancyGridBuilder::labelsOf(ClassPalette(), {"person"}));
  const OccupancyGrid grid = builder.build(octree, floor);
  EXPECT_EQ(state(grid, wall, beside), OccupancyGrid::kOccupied);
  EXPECT_EQ(state(grid, 1.0, 0.0), OccupancyGrid::kFree);
  EXPECT_EQ(state(grid, 2.5, beside), OccupancyGrid::kFree);
  int i = 0, j = 0;
  for (double left = -0.15; left <= 0.23; left += 0.01) {
    if (grid.cellOf({person, left}, &i, &j)) {
      EXPECT_NE(grid.at(i, j), OccupancyGrid::kOccupied) << left;
    }
  }
  // Without the class the person is an obstacle.
  const OccupancyGrid blind = OccupancyGridBuilder(options, {}).build(octree, floor);
  EXPECT_EQ(state(blind, person, 0.0), OccupancyGrid::kOccupied);
  EXPECT_EQ(state(blind, wall, beside), OccupancyGrid::kOccupied);
}

class GridFilesTest : public ::testing::Test {
 protected:
  TempDir temp_;
  const fs::path& dir_ = temp_.path();
};

// map_server's documented reading of a trinary map (negate 0): p = (255 - value) / 255,
// occupied above occupied_thresh, free below free_thresh, unknown between.
std::int8_t mapServerCell(int value, double occupied_thresh, double free_thresh) {
  const double p = (255.0 - value) / 255.0;
  if (p > occupied_thresh) return OccupancyGrid::kOccupied;
  if (p < free_thresh) return OccupancyGrid::kFree;
  return OccupancyGrid::kUnknown;
}

TEST_F(GridFilesTest, MapYamlAndPgmReadBackAsMapServerReadsThem) {
  FloorFrame floor;
  OccupancyGrid grid(4, 3, 0.05, Eigen::Vector2d(-0.1, 0.25), floor);
  grid.set(0, 0, OccupancyGrid::kOccupied);  // the origin's cell: bottom-left of the image
  grid.set(3, 0, OccupancyGrid::kFree);
  grid.set(1, 2, OccupancyGrid::kOccupied);  // top row
  grid.set(2, 1, OccupancyGrid::kFree);
  // The floor frame placed in `map` 2 m along x, turned by 90 deg.
  Eigen::Isometry3d T_map_floor = Eigen::Isometry3d::Identity();
  T_map_floor.linear() = Eigen::AngleAxisd(kPi / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T_map_floor.translation() = Eigen::Vector3d(2.0, 0.0, 0.0);
  const auto written = writeGridMap(dir_.string(), grid, T_map_floor);
  ASSERT_EQ(written.size(), 2u);

  const YAML::Node yaml = YAML::LoadFile((dir_ / "map.yaml").string());
  ASSERT_EQ(yaml["image"].as<std::string>(), "map.pgm");
  EXPECT_DOUBLE_EQ(yaml["resolution"].as<double>(), 0.05);
  const auto origin = yaml["origin"].as<std::vector<double>>();
  ASSERT_EQ(origin.size(), 3u);
  EXPECT_NEAR(origin[0], 2.0 - 0.25, 1e-7);  // (-0.1, 0.25) turned by 90 deg: (-0.25, -0.1)
  EXPECT_NEAR(origin[1], -0.1, 1e-7);
  EXPECT_NEAR(origin[2], kPi / 2, 1e-7);  // 9 digits written
  EXPECT_EQ(yaml["negate"].as<int>(), 0);
  const double occupied_thresh = yaml["occupied_thresh"].as<double>();
  const double free_thresh = yaml["free_thresh"].as<double>();

  const cv::Mat image =
      cv::imread((dir_ / yaml["image"].as<std::string>()).string(), cv::IMREAD_UNCHANGED);
  ASSERT_EQ(image.type(), CV_8UC1);
  ASSERT_EQ(image.cols, 4);
  ASSERT_EQ(image.rows, 3);
  std::set<int> values;
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 4; ++i) {
      const int value = image.at<std::uint8_t>(2 - j, i);
      values.insert(value);
      EXPECT_EQ(mapServerCell(value, occupied_thresh, free_thresh), grid.at(i, j)) << i << "," << j;
    }
  EXPECT_EQ(values, (std::set<int>{0, 205, 254}));
  EXPECT_EQ(image.at<std::uint8_t>(2, 0), 0);    // cell (0, 0), bottom-left
  EXPECT_EQ(image.at<std::uint8_t>(0, 1), 0);    // cell (1, 2), top row
  EXPECT_EQ(image.at<std::uint8_t>(2, 3), 254);  // cell (3, 0)
  EXPECT_EQ(image.at<std::uint8_t>(0, 0), 205);
}

}  // namespace
}  // namespace ply_slam
