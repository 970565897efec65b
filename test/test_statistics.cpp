// The one median and percentile (common/statistics.h) the tools, nodes and evaluation use.
#include <gtest/gtest.h>

#include <vector>

#include "ply_slam/common/latency_window.h"
#include "ply_slam/common/statistics.h"

namespace ply_slam {
namespace {

TEST(Statistics, MedianIsTheMiddleOrTheMeanOfTheTwoMiddles) {
  EXPECT_EQ(median({5.0, 1.0, 3.0}), 3.0);
  EXPECT_EQ(median({4.0, 1.0, 3.0, 10.0}), 3.5);
  EXPECT_EQ(median({7.0}), 7.0);
  EXPECT_EQ(median({}, -1.0), -1.0);
  // Bit for bit numpy's 0.5 * (a + b), as the ATE median always was.
  const double a = 0.1, b = 0.7;
  EXPECT_EQ(median({b, a}), 0.5 * (a + b));
}

TEST(Statistics, PercentileInterpolatesBetweenTheNearestRanks) {
  const std::vector<double> v = {10.0, 0.0, 30.0, 20.0, 40.0};  // sorted: 0 10 20 30 40
  EXPECT_EQ(percentile(v, 0.0), 0.0);
  EXPECT_EQ(percentile(v, 1.0), 40.0);
  EXPECT_EQ(percentile(v, 0.5), median(v));
  EXPECT_DOUBLE_EQ(percentile(v, 0.95), 38.0);  // position 3.8: 30 + 0.8 * 10
  EXPECT_DOUBLE_EQ(percentile(v, 0.125), 5.0);  // position 0.5
  EXPECT_EQ(percentile(v, 2.0), 40.0);          // q is clamped to [0, 1]
  EXPECT_EQ(percentile({}, 0.95, 0.0), 0.0);
}

TEST(Statistics, UpperMedianAndKthSmallestAreValuesOfTheSample) {
  EXPECT_EQ(upperMedian({4.0, 1.0, 3.0, 10.0}), 4.0);
  EXPECT_EQ(upperMedian({5.0, 1.0, 3.0}), 3.0);
  EXPECT_EQ(kthSmallest({4.0, 1.0, 3.0, 10.0}, 0), 1.0);
  EXPECT_EQ(kthSmallest({4.0, 1.0, 3.0, 10.0}, 3), 10.0);
}

}  // namespace
// A node that runs for hours keeps its percentiles over the recent window, its maximum over all.
TEST(LatencyWindow, PercentilesOverTheRecentSamplesMaximumOverAll) {
  LatencyWindow window(4);
  EXPECT_EQ(window.percentile(0.5), 0.0);
  for (double s : {9.0, 1.0, 2.0, 3.0, 4.0}) window.add(s);
  EXPECT_EQ(window.count(), 5u);
  EXPECT_EQ(window.max(), 9.0);
  EXPECT_DOUBLE_EQ(window.percentile(0.5), 2.5);  // of 1, 2, 3, 4: the 9 has left the window
  EXPECT_DOUBLE_EQ(window.percentile(1.0), 4.0);
}

}  // namespace ply_slam
