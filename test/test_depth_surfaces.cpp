// DepthSurfaces: a depth image split at depth steps, on hand-made depth images whose
// surfaces are known.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <opencv2/core.hpp>

#include "ply_slam/dynamic/depth_surfaces.h"

namespace ply_slam {
namespace {

DepthNoiseModel kinectNoise() { return DepthNoiseModel{}; }  // sigma 5 mm at 1 m

// A wall 3 m away with a person-sized box 1 m away in front of it.
cv::Mat wallWithBox(const cv::Rect& box) {
  cv::Mat depth(480, 640, CV_32FC1, cv::Scalar(3.0f));
  depth(box).setTo(1.0f);
  return depth;
}

TEST(DepthSurfaces, BoxInFrontOfAWallIsASurfaceOfItsOwn) {
  const cv::Rect box(200, 100, 160, 300);
  const DepthSurfaces surfaces(wallWithBox(box), kinectNoise());
  ASSERT_EQ(surfaces.count(), 2);
  const int person = surfaces.at({280, 250}), wall = surfaces.at({50, 50});
  EXPECT_NE(person, 0);
  EXPECT_NE(wall, 0);
  EXPECT_NE(person, wall);
  EXPECT_EQ(surfaces.at({600, 460}), wall);  // the wall around the box is one surface
  // Its mask covers the box but for the rim beside the step (a pixel of the half-size image).
  const cv::Mat mask = surfaces.paint({{person, 255}}, 0);
  const int inside = cv::countNonZero(mask(box));
  EXPECT_GT(inside, 0.95 * box.area());
  EXPECT_EQ(cv::countNonZero(mask) - inside, 0);
}

TEST(DepthSurfaces, SlantedFloorStaysOneSurface) {
  // A floor seen from 1.4 m up by a camera looking 20 degrees down: depth grows quickly with
  // the rows up to 5 m, a slope the step must not take for an edge.
  const double fy = 540.0, cy = 240.0, height = 1.4, tilt = 20.0 * M_PI / 180.0;
  cv::Mat depth(480, 640, CV_32FC1, cv::Scalar(0.0f));
  for (int v = 0; v < depth.rows; ++v) {
    const double down = std::atan((v - cy) / fy) + tilt;  // ray angle below the horizon
    if (down <= 0.0) continue;
    const double range = height / std::sin(down);
    const double z = range * std::cos(down - tilt);  // along the optical axis
    if (z < 5.0) depth.row(v).setTo(static_cast<float>(z));
  }
  const DepthSurfaces surfaces(depth, kinectNoise());
  EXPECT_EQ(surfaces.count(), 1);
  EXPECT_NE(surfaces.at({320, 470}), 0);
  EXPECT_EQ(surfaces.at({320, 470}), surfaces.at({320, 300}));
}

TEST(DepthSurfaces, InvalidDepthAndSpecklesBelongToNoSurface) {
  cv::Mat depth = wallWithBox({200, 100, 160, 300});
  depth(cv::Rect(0, 0, 100, 100)).setTo(0.0f);
  depth(cv::Rect(500, 0, 100, 100)).setTo(std::numeric_limits<float>::quiet_NaN());
  depth(cv::Rect(450, 300, 10, 10)).setTo(1.5f);  // 100 px: below min_pixels (400)
  const DepthSurfaces surfaces(depth, kinectNoise());
  EXPECT_EQ(surfaces.count(), 2);
  EXPECT_EQ(surfaces.at({50, 50}), 0);
  EXPECT_EQ(surfaces.at({550, 50}), 0);
  EXPECT_EQ(surfaces.at({455, 305}), 0);
  EXPECT_EQ(surfaces.at({-5, 10}), 0);  // outside the image
}

TEST(DepthSurfaces, OverlapGivesShareAndMedianOfAPaintedImage) {
  const cv::Rect box(200, 100, 160, 300);
  const DepthSurfaces surfaces(wallWithBox(box), kinectNoise());
  const int person = surfaces.at({280, 250});
  // Ages painted on the box's left half: 2 on its top quarter, 4 below.
  cv::Mat ages(480, 640, CV_8UC1, cv::Scalar(255));
  ages(cv::Rect(200, 100, 80, 75)).setTo(2);
  ages(cv::Rect(200, 175, 80, 225)).setTo(4);
  const auto overlap = surfaces.overlap(ages, 255);
  EXPECT_NEAR(overlap[person - 1].share, 0.5, 0.03);
  EXPECT_EQ(overlap[person - 1].median, 4);
  const int wall = surfaces.at({50, 50});
  EXPECT_EQ(overlap[wall - 1].share, 0.0);
  // paint() is the inverse: the box painted with 7 reads back as 7 everywhere on it.
  const auto again = surfaces.overlap(surfaces.paint({{person, 7}}, 255), 255);
  EXPECT_DOUBLE_EQ(again[person - 1].share, 1.0);
  EXPECT_EQ(again[person - 1].median, 7);
}

TEST(DepthSurfaces, RefusesWhatIsNotAMetricDepthImage) {
  EXPECT_THROW(DepthSurfaces(cv::Mat(), kinectNoise()), std::invalid_argument);
  EXPECT_THROW(DepthSurfaces(cv::Mat(480, 640, CV_16UC1, cv::Scalar(1000)), kinectNoise()),
               std::invalid_argument);
}

}  // namespace
}  // namespace ply_slam
