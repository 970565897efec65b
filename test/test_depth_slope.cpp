// The depth image's slope under a feature: exact on a tilted plane, the surface's own slope
// beside a depth edge, one-sided beside a hole, none without depth.
#include <gtest/gtest.h>

#include "ply_slam/features/depth_slope.h"

namespace ply_slam {
namespace {

// Z = 2 + 0.01 u + 0.002 v m, with a step of +1 m from column 50 on.
cv::Mat tiltedPlaneWithStep() {
  cv::Mat depth(40, 100, CV_32FC1);
  for (int v = 0; v < depth.rows; ++v)
    for (int u = 0; u < depth.cols; ++u)
      depth.at<float>(v, u) = 2.f + 0.01f * u + 0.002f * v + (u >= 50 ? 1.f : 0.f);
  return depth;
}

TEST(DepthSlope, TiltedPlaneGivesItsSlope) {
  const Eigen::Vector2d s = depthSlopeAt(tiltedPlaneWithStep(), 20, 10);
  EXPECT_NEAR(s.x(), 0.01, 1e-5);
  EXPECT_NEAR(s.y(), 0.002, 1e-5);
}

TEST(DepthSlope, ADepthEdgeBesideIsNotTheSlope) {
  const cv::Mat depth = tiltedPlaneWithStep();
  EXPECT_NEAR(depthSlopeAt(depth, 49, 10).x(), 0.01, 1e-5);  // the step lies ahead
  EXPECT_NEAR(depthSlopeAt(depth, 50, 10).x(), 0.01, 1e-5);  // the step lies behind
}

TEST(DepthSlope, HolesAndBordersLeaveOneSide) {
  cv::Mat depth = tiltedPlaneWithStep();
  depth.at<float>(10, 21) = 0.f;
  depth.at<float>(10, 22) = std::numeric_limits<float>::quiet_NaN();
  EXPECT_NEAR(depthSlopeAt(depth, 20, 10).x(), 0.01, 1e-5);  // from column 19
  EXPECT_NEAR(depthSlopeAt(depth, 0, 0).x(), 0.01, 1e-5);    // image border
  depth.at<float>(10, 19) = 0.f;
  EXPECT_EQ(depthSlopeAt(depth, 20, 10).x(), 0.0);  // no neighbour in u
  EXPECT_NEAR(depthSlopeAt(depth, 20, 10).y(), 0.002, 1e-5);
  EXPECT_EQ(depthSlopeAt(depth, 22, 10), Eigen::Vector2d::Zero());  // no depth of its own
}

TEST(DepthSlope, FeaturesWithoutADepthImageHaveNone) {
  FrameFeatures f;
  f.keypoints.resize(3);
  const auto slopes = depthSlopes(f);
  ASSERT_EQ(slopes.size(), 3u);
  for (const auto& s : slopes) EXPECT_EQ(s, Eigen::Vector2d::Zero());
}

}  // namespace
}  // namespace ply_slam
