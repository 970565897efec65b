// MapLine::fuse: the fits of one line from the frames that see it averaged into the landmark;
// MapLine::distanceToLine, which the tracker uses to keep other lines' fits out.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "ply_slam/map/map_line.h"

namespace ply_slam {
namespace {

double angleDeg(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::acos(std::min(1.0, std::abs(a.normalized().dot(b.normalized())))) * 180.0 / M_PI;
}

TEST(MapLine, FirstFitIsTakenAsItIs) {
  MapLine l;
  l.fuse({1, 2, 3}, {2, 2, 3}, 4.0, 5.0);
  EXPECT_TRUE(l.start.isApprox(Eigen::Vector3d(1, 2, 3)));
  EXPECT_TRUE(l.end.isApprox(Eigen::Vector3d(2, 2, 3)));
  EXPECT_DOUBLE_EQ(l.start_weight, 4.0);
  EXPECT_DOUBLE_EQ(l.end_weight, 5.0);
}

TEST(MapLine, FitsAreAveragedByTheirWeights) {
  MapLine l;
  l.fuse({0, 0, 2}, {1, 0, 2}, 1.0, 1.0);
  l.fuse({0, 0.4, 2}, {1, 0, 2.4}, 3.0, 1.0);
  EXPECT_TRUE(l.start.isApprox(Eigen::Vector3d(0, 0.3, 2)));  // (0 * 1 + 0.4 * 3) / 4
  EXPECT_TRUE(l.end.isApprox(Eigen::Vector3d(1, 0, 2.2)));    // (2 + 2.4) / 2
  EXPECT_DOUBLE_EQ(l.start_weight, 4.0);
  EXPECT_DOUBLE_EQ(l.end_weight, 2.0);
}

TEST(MapLine, AFitRunningTheOtherWayIsTurnedRound) {
  MapLine same, reversed;
  for (MapLine* l : {&same, &reversed}) l->fuse({0, 0, 2}, {1, 0, 2}, 1.0, 2.0);
  same.fuse({0, 0.2, 2}, {1, 0.2, 2}, 1.0, 2.0);
  reversed.fuse({1, 0.2, 2}, {0, 0.2, 2}, 2.0, 1.0);
  EXPECT_TRUE(reversed.start.isApprox(same.start));
  EXPECT_TRUE(reversed.end.isApprox(same.end));
  EXPECT_DOUBLE_EQ(reversed.start_weight, same.start_weight);
}

TEST(MapLine, AFitWithoutWeightLeavesTheLineAlone) {
  MapLine l;
  l.fuse({0, 0, 2}, {1, 0, 2}, 1.0, 1.0);
  l.fuse({5, 5, 5}, {6, 5, 5}, 0.0, 1.0);
  l.fuse({5, 5, 5}, {6, 5, 5}, 1.0, -1.0);
  EXPECT_TRUE(l.start.isApprox(Eigen::Vector3d(0, 0, 2)));
  EXPECT_TRUE(l.end.isApprox(Eigen::Vector3d(1, 0, 2)));
  EXPECT_DOUBLE_EQ(l.start_weight + l.end_weight, 2.0);
}

TEST(MapLine, DistanceToLineIsTakenFromTheInfiniteLine) {
  MapLine l;
  l.fuse({0, 0, 2}, {1, 0, 2}, 1.0, 1.0);
  EXPECT_NEAR(l.distanceToLine({0.5, 0.03, 2}), 0.03, 1e-12);
  EXPECT_NEAR(l.distanceToLine({3.0, 0.0, 2.04}), 0.04, 1e-12);  // beyond the end: still the line
  EXPECT_NEAR(l.distanceToLine({-1.0, 0.0, 2.0}), 0.0, 1e-12);
}

// Twenty fits of a 0.3 m segment 4 m away, ends off by 1.5 cm (the sensor's sigma there): one
// fit's direction is off by about 4 degrees, the landmark's after all of them by well under half
// of that (1 / sqrt(20) on average; 1.4 degrees with this seed).
TEST(MapLine, FusingFitsNarrowsTheDirection) {
  const Eigen::Vector3d a(-0.15, 0.1, 4.0), b(0.15, 0.1, 4.05);
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, 0.015);
  auto jitter = [&](const Eigen::Vector3d& p) {
    return Eigen::Vector3d(p + Eigen::Vector3d(noise(rng), noise(rng), noise(rng)));
  };
  MapLine l;
  std::vector<double> single;
  for (int k = 0; k < 20; ++k) {
    const Eigen::Vector3d s = jitter(a), e = jitter(b);
    single.push_back(angleDeg(e - s, b - a));
    l.fuse(s, e, 1.0, 1.0);
  }
  std::nth_element(single.begin(), single.begin() + 10, single.end());
  const double fused = angleDeg(l.end - l.start, b - a);
  std::cout << "[ measured ] direction error: one fit median " << single[10] << " deg, fused "
            << fused << " deg\n";
  EXPECT_LT(fused, 0.5 * single[10]);
  EXPECT_LT((l.start - a).norm(), 0.015);
  EXPECT_LT((l.end - b).norm(), 0.015);
}

}  // namespace
}  // namespace ply_slam
