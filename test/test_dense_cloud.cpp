// Dense module, clouds: KeyFrameCloudBuilder (what is left out, labels, undistortion, bad
// packets), the voxel filter, DenseMap placement and pose updates, ClassPalette.
#include <gtest/gtest.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <opencv2/calib3d.hpp>
#include <random>
#include <set>

#include "dense_test_scene.h"
#include "ply_slam/dense/class_palette.h"
#include "ply_slam/dense/dense_map.h"
#include "ply_slam/dense/key_frame_cloud_builder.h"
#include "ply_slam/dense/voxel_filter.h"

namespace ply_slam {
namespace {

using test::kWalkerDepth;
using test::kWalkerPixels;
using test::kWallDepth;
using test::wallPacket;

// Stride 1 and a voxel far smaller than the pixel footprint: one point per used pixel.
DenseOptions everyPixel() { return test::denseTestParams(1, 0.001); }

bool onWalker(const pcl::PointXYZRGBL& p) { return std::abs(p.z - kWalkerDepth) < 1e-4; }

// The one point at depth z (the voxel filter reorders points; a unique depth finds a pixel's).
const pcl::PointXYZRGBL& pointAtDepth(const DenseCloud& cloud, float z) {
  for (const auto& p : cloud.points)
    if (std::abs(p.z - z) < 1e-5f) return p;
  throw std::runtime_error("no point at depth " + std::to_string(z));
}

TEST(KeyFrameCloudBuilder, KeepsEveryValidPixelWithColourAndClass) {
  const ClassPalette palette;
  const KeyFrameCloudBuilder builder(everyPixel(), palette);
  const auto packet = wallPacket(1, Eigen::Vector3d::Zero(), true, false);
  packet->depth.at<float>(0, 0) = 2.0f;  // a bump in the wall marks pixel (0, 0)
  const KeyFrameCloud cloud = builder.build(*packet);
  ASSERT_EQ(cloud.points->size(), 160u * 120u);
  size_t person = 0;
  for (const auto& p : cloud.points->points) {
    const bool walker = onWalker(p);
    ASSERT_TRUE(walker || std::abs(p.z - kWallDepth) < 1e-4 || p.z == 2.0f) << p.z;
    EXPECT_EQ(p.label, walker ? palette.label("person") : ClassPalette::kUnknown);
    EXPECT_EQ(int(p.r), walker ? 255 : 160);  // images are BGR: wall (200, 180, 160)
    EXPECT_EQ(int(p.b), walker ? 0 : 200);
    person += walker;
  }
  EXPECT_EQ(person, static_cast<size_t>(kWalkerPixels.area()));
  // Pinhole without distortion: the pixel (u, v) at depth z is ((u - cx) z / fx, ...).
  const auto& corner = pointAtDepth(*cloud.points, 2.0f);
  const PinholeCamera& camera = packet->camera;
  EXPECT_NEAR(corner.x, (0 - camera.cx) * 2.0 / camera.fx, 1e-5);
  EXPECT_NEAR(corner.y, (0 - camera.cy) * 2.0 / camera.fy, 1e-5);
}

TEST(KeyFrameCloudBuilder, LeavesOutDynamicPixelsInvalidDepthAndOutOfRange) {
  const KeyFrameCloudBuilder builder(everyPixel(), ClassPalette());
  auto packet = wallPacket(1, Eigen::Vector3d::Zero(), true, true);
  packet->depth.at<float>(0, 0) = 0.0f;                                     // no depth
  packet->depth.at<float>(0, 1) = std::numeric_limits<float>::quiet_NaN();  // broken depth
  packet->depth.at<float>(0, 2) = 0.2f;                                     // too near
  packet->depth.at<float>(0, 3) = 4.5f;                                     // too far
  const KeyFrameCloud cloud = builder.build(*packet);
  EXPECT_EQ(cloud.points->size(), 160u * 120u - kWalkerPixels.area() - 4);
  for (const auto& p : cloud.points->points) EXPECT_FALSE(onWalker(p));

  // An instance marked dynamic is left out even when the packet carries no dynamic mask.
  packet->dynamic_mask.release();
  EXPECT_EQ(builder.build(*packet).points->size(), 160u * 120u - kWalkerPixels.area() - 4);
}

TEST(KeyFrameCloudBuilder, DilationWidensTheLeftOutRegion) {
  DenseOptions params = everyPixel();
  params.dilation_px = 2;
  const KeyFrameCloudBuilder builder(params, ClassPalette());
  const auto packet = wallPacket(1, Eigen::Vector3d::Zero(), true, true);
  const size_t kept = builder.build(*packet).points->size();
  // An elliptic 5x5 kernel grows the 40x90 rectangle to 44x94 less 2 px at each corner.
  EXPECT_EQ(kept, 160u * 120u - (44u * 94u - 8u));
}

TEST(KeyFrameCloudBuilder, StrideSamplesEveryNthPixel) {
  DenseOptions params = everyPixel();
  params.stride = 4;
  const KeyFrameCloudBuilder builder(params, ClassPalette());
  const auto packet = wallPacket(1, Eigen::Vector3d::Zero(), false, false);
  EXPECT_EQ(builder.build(*packet).points->size(), (160u / 4) * (120u / 4));
}

TEST(KeyFrameCloudBuilder, UndistortsRawPixels) {
  const KeyFrameCloudBuilder builder(everyPixel(), ClassPalette());
  auto packet = wallPacket(1, Eigen::Vector3d::Zero(), false, false);
  packet->camera.distortion = (cv::Mat_<double>(1, 5) << 0.2, -0.3, 0.001, -0.002, 0.1);
  packet->depth.at<float>(7, 10) = 2.0f;
  const KeyFrameCloud cloud = builder.build(*packet);
  ASSERT_EQ(cloud.points->size(), 160u * 120u);
  // The point of raw pixel (10, 7) lies on the ray OpenCV undistorts that pixel to.
  std::vector<cv::Point2f> raw{{10.f, 7.f}}, ray;
  cv::undistortPoints(raw, ray, cv::Mat(packet->camera.K()), packet->camera.distortion);
  const auto& p = pointAtDepth(*cloud.points, 2.0f);
  EXPECT_NEAR(p.x / p.z, ray[0].x, 1e-5);
  EXPECT_NEAR(p.y / p.z, ray[0].y, 1e-5);
  // and not on the distorted one.
  EXPECT_GT(std::abs(p.x / p.z - (10 - packet->camera.cx) / packet->camera.fx), 1e-3);
}

TEST(KeyFrameCloudBuilder, TagsFollowTheTagMaskThroughTheVoxelFilter) {
  DenseOptions params = everyPixel();
  params.voxel_size = 0.05;
  const KeyFrameCloudBuilder builder(params, ClassPalette());
  const auto packet = wallPacket(1, Eigen::Vector3d::Zero(), true, false);
  cv::Mat tags = cv::Mat::zeros(packet->depth.size(), CV_8UC1);
  tags(kWalkerPixels).setTo(1);
  const KeyFrameCloud cloud = builder.build(*packet, tags);
  ASSERT_TRUE(cloud.tags);
  ASSERT_EQ(cloud.tags->size(), cloud.points->size());
  size_t tagged = 0;
  for (size_t i = 0; i < cloud.points->size(); ++i) {
    EXPECT_EQ(cloud.tags->points[i].label == 1, onWalker(cloud.points->points[i])) << i;
    tagged += cloud.tags->points[i].label;
  }
  EXPECT_GT(tagged, 0u);
}

TEST(KeyFrameCloudBuilder, RejectsBadPacketsNamingTheFault) {
  const KeyFrameCloudBuilder builder(everyPixel(), ClassPalette());
  const auto good = wallPacket(3, Eigen::Vector3d::Zero(), true, true);
  auto expectRejected = [&](KeyFramePacket packet, const std::string& what) {
    try {
      builder.build(packet);
      ADD_FAILURE() << "accepted a packet with " << what;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("keyframe 3"), std::string::npos) << e.what();
    }
  };
  KeyFramePacket p = *good;
  p.depth.release();
  expectRejected(p, "depth");
  p = *good;
  p.depth.convertTo(p.depth, CV_16UC1);
  expectRejected(p, "depth");
  p = *good;
  p.rgb = cv::Mat(60, 80, CV_8UC3);
  expectRejected(p, "rgb and depth differ");
  p = *good;
  p.camera.width = 640;
  expectRejected(p, "camera's size");
  p = *good;
  p.label_image = cv::Mat::zeros(120, 160, CV_8UC1);
  expectRejected(p, "label_image");
  p = *good;
  p.dynamic_mask = cv::Mat::zeros(10, 10, CV_8UC1);
  expectRejected(p, "dynamic_mask");
  EXPECT_THROW(builder.build(*good, cv::Mat::zeros(10, 10, CV_8UC1)), std::invalid_argument);
  // The builder is still usable.
  EXPECT_EQ(builder.build(*good).points->size(), 160u * 120u - kWalkerPixels.area());
}

TEST(VoxelFilter, OnePointPerVoxelInsideTheVoxel) {
  DenseCloud cloud;
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(0.f, 1.f);
  for (int i = 0; i < 20000; ++i) {
    pcl::PointXYZRGBL p;
    p.x = u(rng), p.y = u(rng), p.z = u(rng);
    p.label = i % 3 == 0 ? 5 : 9;  // 9 is the majority
    cloud.push_back(p);
  }
  const double leaf = 0.1;
  const DenseCloudPtr out = voxelFilter(cloud, leaf);
  EXPECT_LE(out->size(), 1000u);  // 10 x 10 x 10 voxels in the unit cube
  EXPECT_GE(out->size(), 990u);   // 20 points a voxel on average: all are hit
  std::set<long> voxels;
  size_t majority = 0;
  for (const auto& p : out->points) {
    EXPECT_TRUE(p.x >= 0.f && p.x <= 1.f && p.y >= 0.f && p.y <= 1.f && p.z >= 0.f && p.z <= 1.f);
    const long key = long(p.x / leaf) * 10000 + long(p.y / leaf) * 100 + long(p.z / leaf);
    EXPECT_TRUE(voxels.insert(key).second) << "two points in one voxel";
    majority += p.label == 9;
  }
  EXPECT_GT(majority, out->size() * 8 / 10);
  EXPECT_THROW(voxelFilter(cloud, 0.0), std::invalid_argument);
}

TEST(VoxelFilter, FiltersCloudsTooLargeForOneVoxelGrid) {
  // 100 m x 100 m x 1 m at 1 cm: 1e10 voxels, beyond VoxelGrid's 32-bit voxel numbers.
  DenseCloud cloud;
  for (const float x : {0.f, 100.f})
    for (const float y : {0.f, 100.f})
      for (const float z : {0.f, 1.f})
        for (int i = 0; i < 3; ++i) {
          pcl::PointXYZRGBL p;
          p.x = x + 0.001f * i + 0.002f, p.y = y + 0.002f, p.z = z + 0.002f;
          cloud.push_back(p);
        }
  const DenseCloudPtr out = voxelFilter(cloud, 0.01);
  EXPECT_EQ(out->size(), 8u);  // one point per corner, from three
}

// A point at NaN or infinity (a camera with a NaN distortion, fx 1e-300) has no voxel: it is
// left out, not split for ever (that overflowed the stack).
TEST(VoxelFilter, LeavesOutPointsThatAreNotFinite) {
  DenseCloud cloud;
  const float inf = std::numeric_limits<float>::infinity();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  for (const float bad : {inf, -inf, nan}) {
    pcl::PointXYZRGBL p;
    p.x = 0.5f, p.y = bad, p.z = 1.f;
    cloud.push_back(p);
  }
  pcl::PointXYZRGBL good;
  good.x = 0.01f, good.y = 0.02f, good.z = 0.03f;
  cloud.push_back(good);
  cloud.push_back(good);
  const DenseCloudPtr out = voxelFilter(cloud, 0.05);
  ASSERT_EQ(out->size(), 1u);
  EXPECT_FLOAT_EQ(out->points[0].x, 0.01f);
}

// Points so far apart that float rounding cannot split them are kept as they are.
TEST(VoxelFilter, KeepsHugeButFiniteCloudsWithoutRecursingForEver) {
  DenseCloud cloud;
  for (const float x : {-3e38f, 3e38f}) {
    pcl::PointXYZRGBL p;
    p.x = x, p.y = 0.f, p.z = 1.f;
    cloud.push_back(p);
  }
  EXPECT_EQ(voxelFilter(cloud, 1e-30)->size(), 2u);
}

TEST(DenseMap, PlacesKeyFramesAndRePlacesThoseWhosePoseChanged) {
  DenseMap map(0.01);
  auto one = [](double x, double y, double z) {
    auto cloud = std::make_shared<DenseCloud>();
    pcl::PointXYZRGBL p;
    p.x = x, p.y = y, p.z = z, p.label = 0;
    cloud->push_back(p);
    return cloud;
  };
  KeyFrameCloud a, b;
  a.id = 1;
  a.points = one(0, 0, 1);
  b.id = 2;
  b.points = one(0, 0, 2);
  b.T_wc.translation() = Eigen::Vector3d(5, 0, 0);
  map.insert(a);
  map.insert(b);
  DenseCloudPtr global = map.globalCloud();
  ASSERT_EQ(global->size(), 2u);
  std::set<std::pair<int, int>> xz;
  for (const auto& p : global->points) xz.insert({int(std::lround(p.x)), int(std::lround(p.z))});
  EXPECT_EQ(xz, (std::set<std::pair<int, int>>{{0, 1}, {5, 2}}));

  MapUpdate update;
  Eigen::Isometry3d moved = Eigen::Isometry3d::Identity();
  moved.translation() = Eigen::Vector3d(-3, 0, 0);
  update.keyframes.push_back({1, moved.inverse()});
  update.keyframes.push_back({2, b.T_wc.inverse()});                // unchanged
  update.keyframes.push_back({99, Eigen::Isometry3d::Identity()});  // unknown: ignored
  EXPECT_EQ(map.applyUpdate(update), std::vector<long>{1});
  global = map.globalCloud();
  xz.clear();
  for (const auto& p : global->points) xz.insert({int(std::lround(p.x)), int(std::lround(p.z))});
  EXPECT_EQ(xz, (std::set<std::pair<int, int>>{{-3, 1}, {5, 2}}));
  EXPECT_EQ(map.taggedPoints(), -1);  // no tags given
  EXPECT_THROW(map.insert(KeyFrameCloud{}), std::invalid_argument);
}

TEST(DenseMap, ErasedKeyFramesLeaveTheGlobalCloud) {
  DenseMap map(0.01);
  for (long id : {1, 2, 3}) {
    KeyFrameCloud cloud;
    cloud.id = id;
    cloud.points = std::make_shared<DenseCloud>();
    pcl::PointXYZRGBL p;
    p.x = 0, p.y = 0, p.z = id, p.label = 0;
    cloud.points->push_back(p);
    map.insert(cloud);
  }
  ASSERT_EQ(map.numGlobalPoints(), 3u);
  EXPECT_EQ(map.erase({2, 99}), 1u);  // 99: unknown, ignored
  EXPECT_EQ(map.numKeyFrames(), 2u);
  const DenseCloudPtr global = map.globalCloud();
  ASSERT_EQ(global->size(), 2u);
  for (const auto& p : global->points) EXPECT_NE(std::lround(p.z), 2);
}

TEST(ClassPalette, OneDistinctColourPerCocoClassAndUnknown) {
  const ClassPalette palette;
  ASSERT_EQ(palette.size(), 81u);
  EXPECT_EQ(palette.label("person"), 1u);
  EXPECT_EQ(palette.label("toothbrush"), 80u);
  EXPECT_EQ(palette.label("wall"), ClassPalette::kUnknown);
  EXPECT_EQ(palette.name(57), "chair");
  std::set<std::tuple<int, int, int>> colours;
  for (std::uint32_t l = 0; l < palette.size(); ++l) {
    const ClassColour c = palette.colour(l);
    colours.insert({c.r, c.g, c.b});
  }
  EXPECT_EQ(colours.size(), 81u);
}

TEST(ClassPalette, FileOverridesColoursAndRejectsUnknownClasses) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("ply_slam_palette_" + std::to_string(getpid()));
  fs::create_directories(dir);
  std::ofstream(dir / "good.txt") << "# comment\n1 2 3 dining table\n";
  const ClassPalette custom = ClassPalette::fromFile((dir / "good.txt").string());
  EXPECT_EQ(custom.colour(custom.label("dining table")), (ClassColour{1, 2, 3}));
  EXPECT_EQ(custom.colour(1), ClassPalette().colour(1));
  std::ofstream(dir / "bad.txt") << "1 2 3 spaceship\n";
  EXPECT_THROW(ClassPalette::fromFile((dir / "bad.txt").string()), std::runtime_error);
  std::ofstream(dir / "range.txt") << "1 2 300 person\n";
  EXPECT_THROW(ClassPalette::fromFile((dir / "range.txt").string()), std::runtime_error);
  EXPECT_THROW(ClassPalette::fromFile((dir / "missing.txt").string()), std::runtime_error);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace ply_slam
