// Relocalisation after a gap in the frames (ply_slam_tum --kidnap / --cover): the gap's
// notation, and how a run through it is judged, on trajectories with known answers.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <stdexcept>

#include "ply_slam/eval/gap_evaluation.h"

namespace ply_slam {
namespace {

constexpr double kPeriod = 1.0 / 30.0;

// A camera turning and moving along a curve, a pose per frame.
Trajectory truth(int n) {
  Trajectory t;
  for (int k = 0; k < n; ++k) {
    StampedPose p;
    p.stamp = 1000.0 + k * kPeriod;
    p.T_wc.linear() =
        Eigen::AngleAxisd(0.02 * k, Eigen::Vector3d(0.3, 1.0, 0.2).normalized()).toRotationMatrix();
    p.T_wc.translation() = Eigen::Vector3d(std::cos(0.05 * k), 0.3 * std::sin(0.07 * k), 0.01 * k);
    t.push_back(p);
  }
  return t;
}

// The run's estimate: the truth in a frame of its own, frames [from, to) missing, and those
// after the gap displaced by `offset` (a relocalisation that put the camera wrong).
Trajectory estimate(const Trajectory& gt, int from, int to, const Eigen::Vector3d& offset) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();  // map frame -> ground-truth frame
  T.linear() = Eigen::AngleAxisd(1.1, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(0.4, -2.0, 1.0);
  Trajectory est;
  for (int k = 0; k < static_cast<int>(gt.size()); ++k) {
    if (k >= from && k < to) continue;
    StampedPose p = gt[k];
    p.T_wc = T.inverse() * p.T_wc;
    if (k >= to) p.T_wc.translation() += offset;
    est.push_back(p);
  }
  return est;
}

TEST(FrameGap, FromToWithAFrameBeforeIt) {
  const auto gap = parseFrameGap("10:40", true);
  ASSERT_TRUE(gap);
  EXPECT_EQ(gap->from, 10);
  EXPECT_EQ(gap->to, 40);
  EXPECT_TRUE(gap->black);
  EXPECT_FALSE(gap->holds(9));
  EXPECT_TRUE(gap->holds(10));
  EXPECT_TRUE(gap->holds(39));
  EXPECT_FALSE(gap->holds(40));
  for (const char* bad : {"0:5", "5:5", "7:3", "a:9", "10", "10:", ":10", "1:2:3", "-1:4", "1: 4"})
    EXPECT_FALSE(parseFrameGap(bad, false)) << bad;
}

TEST(GapEvaluation, ARightRelocalisationHasNoError) {
  const Trajectory gt = truth(120);
  const Trajectory est = estimate(gt, 40, 70, Eigen::Vector3d::Zero());
  const GapReport r = evaluateGap(gt, est, gt[39].stamp, gt[70].stamp, {gt[70].stamp});
  EXPECT_TRUE(r.relocalised);
  EXPECT_LT(r.first_error_m, 1e-9);
  EXPECT_LT(r.first_error_deg, 1e-6);
  EXPECT_EQ(r.after.count, 50u);
  EXPECT_LT(r.after.rmse, 1e-9);
  EXPECT_EQ(r.relocalisations, 1);
  EXPECT_EQ(r.wrong_relocalisations, 0);
}

TEST(GapEvaluation, ARelocalisationInTheWrongPlaceIsWrong) {
  const Trajectory gt = truth(120);
  // 0.3 m off in the map's frame: the error of the first pose and of every pose after it.
  const Trajectory est = estimate(gt, 40, 70, Eigen::Vector3d(0.0, 0.3, 0.0));
  const GapReport r = evaluateGap(gt, est, gt[39].stamp, gt[70].stamp, {gt[70].stamp});
  EXPECT_NEAR(r.first_error_m, 0.3, 1e-9);
  EXPECT_NEAR(r.after.rmse, 0.3, 1e-9);
  EXPECT_EQ(r.relocalisations, 1);
  EXPECT_EQ(r.wrong_relocalisations, 1);
  // Within a looser tolerance it is not wrong; a stamp with no pose is no relocalisation.
  const GapReport loose = evaluateGap(gt, est, gt[39].stamp, gt[70].stamp,
                                      {gt[70].stamp, gt[50].stamp}, GapTolerance{0.5, 5.0});
  EXPECT_EQ(loose.relocalisations, 1);
  EXPECT_EQ(loose.wrong_relocalisations, 0);
}

TEST(GapEvaluation, NothingAfterTheGapAndTooLittleBeforeIt) {
  const Trajectory gt = truth(120);
  const Trajectory est = estimate(gt, 40, 120, Eigen::Vector3d::Zero());  // never again
  const GapReport r = evaluateGap(gt, est, gt[39].stamp, gt[70].stamp, {});
  EXPECT_FALSE(r.relocalised);
  EXPECT_EQ(r.after.count, 0u);
  EXPECT_EQ(r.relocalisations, 0);
  const Trajectory early = estimate(gt, 2, 70, Eigen::Vector3d::Zero());  // 2 poses before it
  EXPECT_THROW(evaluateGap(gt, early, gt[1].stamp, gt[70].stamp, {}), std::runtime_error);
}

}  // namespace
}  // namespace ply_slam
