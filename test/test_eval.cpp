// Evaluation (association, ATE, RPE, plot) and TUM trajectory file I/O, with answers derived
// by hand so that a wrong alignment, association or error definition fails.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "ply_slam/eval/trajectory_association.h"
#include "ply_slam/eval/trajectory_metrics.h"
#include "ply_slam/eval/trajectory_plot.h"
#include "ply_slam/io/tum_trajectory_file.h"
#include "shared_data.h"
#include "temp_dir.h"

namespace ply_slam {
namespace {

namespace fs = std::filesystem;

constexpr double kDegreesPerRadian = 180.0 / 3.14159265358979323846;
constexpr double kBaseStamp = 1305031100.0;  // TUM-like stamps, to exercise their precision

Eigen::Isometry3d makePose(const Eigen::Vector3d& axis, double angle, const Eigen::Vector3d& t) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
  pose.translation() = t;
  return pose;
}

// A curved, non-planar path with changing orientation: the alignment is fully determined.
Trajectory makeTrajectory(int n, double period = 1.0 / 30.0) {
  Trajectory trajectory;
  for (int k = 0; k < n; ++k) {
    StampedPose pose;
    pose.stamp = kBaseStamp + k * period;
    pose.T_wc = makePose(Eigen::Vector3d(1.0, 2.0, 3.0), 0.05 * k,
                         Eigen::Vector3d(std::cos(0.3 * k), 0.8 * std::sin(0.2 * k), 0.05 * k));
    trajectory.push_back(pose);
  }
  return trajectory;
}

Trajectory transformed(const Eigen::Isometry3d& T, Trajectory trajectory) {
  for (StampedPose& pose : trajectory) pose.T_wc = T * pose.T_wc;
  return trajectory;
}

double maxAbsDifference(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return (a.matrix() - b.matrix()).cwiseAbs().maxCoeff();
}

void writeText(const std::string& path, const std::string& text) {
  std::ofstream out(path);
  out << text;
}

std::string readErrorMessage(const std::string& path) {
  try {
    readTumTrajectory(path);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "<no exception>";
}

// ---------------------------------------------------------------- ATE

TEST(Ate, RigidlyMovedCopyHasZeroErrorAndAlignmentIsRecovered) {
  const Trajectory gt = makeTrajectory(60);
  const Eigen::Isometry3d T =
      makePose(Eigen::Vector3d(0.3, -0.5, 0.8), 0.7, Eigen::Vector3d(1.5, -2.0, 0.3));
  const AteResult ate = computeAte(gt, transformed(T, gt));
  EXPECT_EQ(ate.translation.count, 60u);
  EXPECT_LT(ate.translation.rmse, 1e-9);
  EXPECT_LT(ate.translation.max, 1e-9);
  // est = T * gt, so the map from estimate into ground truth is T^-1.
  EXPECT_LT(maxAbsDifference(ate.T_gt_est, T.inverse()), 1e-9);
}

TEST(Ate, ScaledCopyIsAlignedBySimilarityNotByRigidMotion) {
  // The estimate 1/1.15 the size of the truth (a depth sensor reading 13 % short), moved.
  const Trajectory gt = makeTrajectory(60);
  const Eigen::Isometry3d T =
      makePose(Eigen::Vector3d(0.3, -0.5, 0.8), 0.7, Eigen::Vector3d(1.5, -2.0, 0.3));
  Trajectory est = transformed(T, gt);
  for (StampedPose& pose : est) pose.T_wc.translation() /= 1.15;
  const SimilarityAteResult sim = computeAteSimilarity(gt, est);
  EXPECT_EQ(sim.translation.count, 60u);
  EXPECT_NEAR(sim.scale, 1.15, 1e-9);
  EXPECT_LT(sim.translation.rmse, 1e-9);
  EXPECT_GT(computeAte(gt, est).translation.rmse, 1e-3);  // a rigid motion cannot fit it
  // Unscaled, the two alignments agree.
  const SimilarityAteResult same = computeAteSimilarity(gt, transformed(T, gt));
  EXPECT_NEAR(same.scale, 1.0, 1e-9);
  EXPECT_THROW(alignSimilarity({}, {}), std::invalid_argument);
}

TEST(Ate, AlignRigidRecoversTransformOfPoints) {
  std::vector<Eigen::Vector3d> gt, est;
  const Eigen::Isometry3d T =
      makePose(Eigen::Vector3d(-1.0, 0.2, 0.4), 2.5, Eigen::Vector3d(-0.4, 0.9, 3.0));
  for (const StampedPose& pose : makeTrajectory(10)) {
    gt.push_back(pose.T_wc.translation());
    est.push_back(T * pose.T_wc.translation());
  }
  EXPECT_LT(maxAbsDifference(alignRigid(est, gt), T.inverse()), 1e-9);
  EXPECT_THROW(alignRigid(est, {}), std::invalid_argument);

  // Planar points (a robot on the floor): the cross-covariance has rank 2 and, without the
  // determinant check, the SVD may return the mirror image through the plane.
  std::vector<Eigen::Vector3d> planar_gt, planar_est;
  for (int k = 0; k < 12; ++k) {
    planar_gt.emplace_back(std::cos(0.5 * k) * (1.0 + 0.1 * k), std::sin(0.7 * k), 0.0);
    planar_est.push_back(T * planar_gt.back());
  }
  const Eigen::Isometry3d planar = alignRigid(planar_est, planar_gt);
  EXPECT_NEAR(planar.linear().determinant(), 1.0, 1e-9);
  EXPECT_LT(maxAbsDifference(planar, T.inverse()), 1e-9);
}

// The camera pauses: every position q_m is held for `group` consecutive stamps, and the first
// pose of each group is displaced by `offset`. Within a group the displacements minus their
// mean sum to zero, so the cross-covariance of the centred point sets is
// group * sum (q_m - q)(q_m - q)^T: symmetric positive definite, the optimal rotation is the
// identity (relative to the applied transform) and the alignment only absorbs the mean
// displacement offset / group. The residuals are then (1 - 1/group) * |offset| for the
// displaced pose and |offset| / group for the others.
Trajectory pausingTrajectory(int positions, int group) {
  const Trajectory path = makeTrajectory(positions);
  Trajectory trajectory;
  for (int m = 0; m < positions; ++m) {
    for (int k = 0; k < group; ++k) {
      StampedPose pose = path[m];
      pose.stamp = kBaseStamp + (m * group + k) * 0.05;
      trajectory.push_back(pose);
    }
  }
  return trajectory;
}

Trajectory displaceFirstOfEachGroup(Trajectory trajectory, int group,
                                    const Eigen::Vector3d& offset) {
  for (size_t k = 0; k < trajectory.size(); k += group) trajectory[k].T_wc.translation() += offset;
  return trajectory;
}

TEST(Ate, OffsetOnHalfThePosesGivesHalfTheOffset) {
  // group 2, offset 0.1 m in x: residuals are 0.05 m everywhere. Without the translation
  // part of the alignment the rmse would be sqrt(0.1^2 / 2) = 0.0707 m.
  const Trajectory gt = pausingTrajectory(20, 2);
  const Eigen::Isometry3d T =
      makePose(Eigen::Vector3d(0.0, 1.0, 1.0), -0.9, Eigen::Vector3d(0.2, 0.1, -1.0));
  const Trajectory est =
      transformed(T, displaceFirstOfEachGroup(gt, 2, Eigen::Vector3d(0.1, 0.0, 0.0)));
  const AteResult ate = computeAte(gt, est);
  EXPECT_EQ(ate.translation.count, 40u);
  EXPECT_NEAR(ate.translation.rmse, 0.05, 1e-9);
  EXPECT_NEAR(ate.translation.mean, 0.05, 1e-9);
  EXPECT_NEAR(ate.translation.median, 0.05, 1e-9);
  EXPECT_NEAR(ate.translation.max, 0.05, 1e-9);
  // Before T is applied the displaced poses shift the centroid by 0.05 m along x; the
  // alignment undoes T and takes that shift back: T_gt_est = shift(-0.05 x) * T^-1.
  Eigen::Isometry3d expected = Eigen::Isometry3d::Identity();
  expected.translation() = Eigen::Vector3d(-0.05, 0.0, 0.0);
  expected = expected * T.inverse();
  EXPECT_LT(maxAbsDifference(ate.T_gt_est, expected), 1e-9);
}

TEST(Ate, OffsetOnAQuarterOfThePosesGivesDistinctStatistics) {
  // group 4, offset 0.1 m in z: residuals 0.075 m (one in four) and 0.025 m (three in four).
  //   rmse   = sqrt((0.075^2 + 3 * 0.025^2) / 4) = sqrt(0.001875) = 0.0433012702
  //   mean   = (0.075 + 3 * 0.025) / 4 = 0.0375
  //   median = 0.025 (the two middle values of the sorted errors are both 0.025)
  //   max    = 0.075
  const Trajectory gt = pausingTrajectory(15, 4);
  const Trajectory est = displaceFirstOfEachGroup(gt, 4, Eigen::Vector3d(0.0, 0.0, 0.1));
  const AteResult ate = computeAte(gt, est);
  EXPECT_EQ(ate.translation.count, 60u);
  EXPECT_NEAR(ate.translation.rmse, std::sqrt(0.001875), 1e-9);
  EXPECT_NEAR(ate.translation.mean, 0.0375, 1e-9);
  EXPECT_NEAR(ate.translation.median, 0.025, 1e-9);
  EXPECT_NEAR(ate.translation.max, 0.075, 1e-9);
}

TEST(Ate, TooFewPairsThrows) {
  const Trajectory gt = makeTrajectory(10);
  Trajectory est(gt.begin(), gt.begin() + 2);
  EXPECT_THROW(computeAte(gt, est), std::runtime_error);
  // Stamps 1 s off do not associate at all.
  Trajectory shifted = gt;
  for (StampedPose& pose : shifted) pose.stamp += 1.0;
  try {
    computeAte(gt, shifted);
    FAIL() << "expected std::runtime_error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("at least 3"), std::string::npos) << e.what();
  }
}

// ---------------------------------------------------------------- association

Trajectory stampsOnly(const std::vector<double>& stamps) {
  Trajectory trajectory;
  for (double s : stamps) trajectory.push_back(StampedPose{s, Eigen::Isometry3d::Identity()});
  return trajectory;
}

TEST(Association, JitteredStampsAndMissingPose) {
  std::vector<double> gt_stamps;
  for (int k = 0; k < 10; ++k) gt_stamps.push_back(10.0 + 0.1 * k);
  // Estimate: pose 4 missing, jitter up to 18 ms, plus a stray stamp 30 ms after gt pose 4
  // appended out of time order.
  const double jitter[10] = {0.004, -0.007, 0.011, -0.015, 0.0, 0.009, -0.003, 0.0, 0.018, -0.012};
  std::vector<double> est_stamps;
  for (int k = 0; k < 10; ++k) {
    if (k != 4) est_stamps.push_back(gt_stamps[k] + jitter[k]);
  }
  est_stamps.push_back(10.43);
  const Trajectory gt = stampsOnly(gt_stamps), est = stampsOnly(est_stamps);

  using Pairs = std::vector<std::pair<size_t, size_t>>;
  const Pairs expected_default = {{0, 0}, {1, 1}, {2, 2}, {3, 3}, {5, 4},
                                  {6, 5}, {7, 6}, {8, 7}, {9, 8}};
  EXPECT_EQ(associateByStamp(gt, est), expected_default);
  // A wider window takes the stray stamp for gt pose 4, still sorted by the first index.
  const Pairs expected_wide = {{0, 0}, {1, 1}, {2, 2}, {3, 3}, {4, 9},
                               {5, 4}, {6, 5}, {7, 6}, {8, 7}, {9, 8}};
  EXPECT_EQ(associateByStamp(gt, est, 0.04), expected_wide);
  // A narrower one drops every pair jittered by more than 10 ms.
  const Pairs expected_narrow = {{0, 0}, {1, 1}, {5, 4}, {6, 5}, {7, 6}};
  EXPECT_EQ(associateByStamp(gt, est, 0.01), expected_narrow);
  // Symmetric in its arguments up to the order of the indices.
  const Pairs swapped = associateByStamp(est, gt);
  ASSERT_EQ(swapped.size(), expected_default.size());
  for (const auto& [ie, ig] : swapped) {
    EXPECT_NE(std::find(expected_default.begin(), expected_default.end(), std::make_pair(ig, ie)),
              expected_default.end());
  }
}

TEST(Association, ClosestPairWinsAndEachPoseIsUsedOnce) {
  // Candidates: (a1,b0) 2 ms, (a0,b0) 8 ms, (a1,b1) 15 ms. Greedy by distance takes (a1,b0);
  // the other two reuse a taken pose, so a0 and b1 stay unpaired although each lies within
  // max_dt of some pose.
  const Trajectory a = stampsOnly({0.000, 0.010});
  const Trajectory b = stampsOnly({0.008, 0.025});
  const std::vector<std::pair<size_t, size_t>> expected = {{1, 0}};
  EXPECT_EQ(associateByStamp(a, b), expected);
  EXPECT_TRUE(associateByStamp(a, stampsOnly({})).empty());
}

// ---------------------------------------------------------------- RPE

TEST(Rpe, ConstantExtraMotionPerStep) {
  // Every estimated step is the true step followed by D, in a different world frame:
  // est_{k+1} = est_k * (gt_k^-1 gt_{k+1}) * D, so (gt_i^-1 gt_{i+1})^-1 (est_i^-1 est_{i+1}) = D.
  const Trajectory gt = makeTrajectory(50);
  const double angle = 2.0 / kDegreesPerRadian;
  const Eigen::Isometry3d D =
      makePose(Eigen::Vector3d(0.2, -1.0, 0.5), angle, Eigen::Vector3d(0.01, -0.02, 0.005));
  Trajectory est = gt;
  est[0].T_wc = makePose(Eigen::Vector3d(1.0, 1.0, 0.0), 1.0, Eigen::Vector3d(5.0, 0.0, -1.0));
  for (size_t k = 0; k + 1 < gt.size(); ++k) {
    est[k + 1].T_wc = est[k].T_wc * (gt[k].T_wc.inverse() * gt[k + 1].T_wc) * D;
  }
  const RpeResult rpe = computeRpeFrames(gt, est, 1);
  const double expected_translation = D.translation().norm();  // sqrt(0.000525) = 0.0229 m
  EXPECT_EQ(rpe.translation.count, 49u);
  EXPECT_NEAR(rpe.translation.rmse, expected_translation, 1e-9);
  EXPECT_NEAR(rpe.translation.mean, expected_translation, 1e-9);
  EXPECT_NEAR(rpe.translation.median, expected_translation, 1e-9);
  EXPECT_NEAR(rpe.translation.max, expected_translation, 1e-9);
  EXPECT_NEAR(rpe.rotation.rmse, 2.0, 1e-9);
  EXPECT_NEAR(rpe.rotation.max, 2.0, 1e-9);
  // The ground truth against itself, moved to another world frame, has no relative error.
  const RpeResult self = computeRpeFrames(gt, transformed(est[0].T_wc, gt), 3);
  EXPECT_LT(self.translation.max, 1e-9);
  EXPECT_LT(self.rotation.max, 1e-9);
}

TEST(Rpe, ExtraMotionOnEveryOtherStepGivesEvenCountStatistics) {
  // D on even steps only: of the 10 one-frame pairs, 5 have error D and 5 none. With an even
  // count the median is the mean of the two middle values, (0 + |D|) / 2, as in numpy.
  const Trajectory gt = makeTrajectory(11);
  const Eigen::Isometry3d D = makePose(Eigen::Vector3d(1.0, 0.0, 0.0), 4.0 / kDegreesPerRadian,
                                       Eigen::Vector3d(0.0, 0.03, 0.04));  // |t| = 0.05 m
  Trajectory est = gt;
  for (size_t k = 0; k + 1 < gt.size(); ++k) {
    const Eigen::Isometry3d step = gt[k].T_wc.inverse() * gt[k + 1].T_wc;
    est[k + 1].T_wc = est[k].T_wc * step * (k % 2 == 0 ? D : Eigen::Isometry3d::Identity());
  }
  const RpeResult rpe = computeRpeFrames(gt, est, 1);
  EXPECT_EQ(rpe.translation.count, 10u);
  EXPECT_NEAR(rpe.translation.median, 0.025, 1e-9);
  EXPECT_NEAR(rpe.translation.mean, 0.025, 1e-9);
  EXPECT_NEAR(rpe.translation.rmse, 0.05 / std::sqrt(2.0), 1e-9);
  EXPECT_NEAR(rpe.translation.max, 0.05, 1e-9);
  EXPECT_NEAR(rpe.rotation.median, 2.0, 1e-9);
  EXPECT_NEAR(rpe.rotation.max, 4.0, 1e-9);
}

TEST(Rpe, LongerDeltaInFramesAndSeconds) {
  // Ground truth translates by g per frame without rotating (G = (I, g)); each estimated step
  // adds a rotation R of theta about z (D = (R, 0)). Over two frames
  //   E = (G G)^-1 (G D G D) = G^-1 D G D = (R^2, R g - g),
  // so the rotation error is 2 theta and the translation error |R g - g| = 2 sin(theta/2) |g|
  // for g in the x-y plane.
  const Eigen::Vector3d g(0.05, 0.02, 0.0);
  const double theta = 3.0 / kDegreesPerRadian;
  const Eigen::Isometry3d D = makePose(Eigen::Vector3d::UnitZ(), theta, Eigen::Vector3d::Zero());
  Trajectory gt, est;
  for (int k = 0; k < 30; ++k) {
    StampedPose pose;
    pose.stamp = kBaseStamp + 0.1 * k;
    pose.T_wc.translation() = k * g;
    gt.push_back(pose);
    if (k > 0) {
      Eigen::Isometry3d step = Eigen::Isometry3d::Identity();
      step.translation() = g;
      pose.T_wc = est.back().T_wc * step * D;
    }
    est.push_back(pose);
  }
  const double expected_translation = 2.0 * std::sin(theta / 2.0) * g.norm();
  const RpeResult frames = computeRpeFrames(gt, est, 2);
  EXPECT_EQ(frames.translation.count, 28u);
  EXPECT_NEAR(frames.translation.rmse, expected_translation, 1e-9);
  EXPECT_NEAR(frames.translation.max, expected_translation, 1e-9);
  EXPECT_NEAR(frames.rotation.rmse, 6.0, 1e-9);
  // 0.2 s and 0.15 s both select the pose two frames (0.2 s) later, despite stamps near 1e9.
  for (double seconds : {0.2, 0.15}) {
    const RpeResult timed = computeRpeSeconds(gt, est, seconds);
    EXPECT_EQ(timed.translation.count, 28u) << seconds;
    EXPECT_NEAR(timed.translation.rmse, expected_translation, 1e-9) << seconds;
    EXPECT_NEAR(timed.rotation.median, 6.0, 1e-9) << seconds;
  }
  EXPECT_THROW(computeRpeFrames(gt, est, 30), std::runtime_error);
  EXPECT_THROW(computeRpeSeconds(gt, est, 5.0), std::runtime_error);
  EXPECT_THROW(computeRpeFrames(gt, est, 0), std::invalid_argument);
}

// ---------------------------------------------------------------- file I/O

TEST(TumTrajectoryFile, RoundTripKeepsPrecision) {
  TempDir dir;
  Trajectory original = makeTrajectory(40);
  original[3].stamp = 1305031098.665912;
  writeTumTrajectory(dir.file("traj.txt"), original);
  const Trajectory read = readTumTrajectory(dir.file("traj.txt"));
  ASSERT_EQ(read.size(), original.size());
  for (size_t k = 0; k < read.size(); ++k) {
    EXPECT_NEAR(read[k].stamp, original[k].stamp, 1e-6) << k;
    EXPECT_LT((read[k].T_wc.translation() - original[k].T_wc.translation()).norm(), 1e-6) << k;
    const Eigen::AngleAxisd rotation_error(read[k].T_wc.linear().transpose() *
                                           original[k].T_wc.linear());
    EXPECT_LT(rotation_error.angle(), 1e-6) << k;
  }
}

TEST(TumTrajectoryFile, ReadsCommentsBlankLinesAndCommas) {
  TempDir dir;
  writeText(dir.file("t.txt"),
            "# ground truth trajectory\n\n  # indented comment\n"
            "1.5 1 2 3 0 0 0 1\r\n"
            "2.5,1,2,3,0,0,0.7071068,0.7071068\n"
            "3.5\t0 0 0 0 0 0 2\n");
  const Trajectory t = readTumTrajectory(dir.file("t.txt"));
  ASSERT_EQ(t.size(), 3u);
  EXPECT_DOUBLE_EQ(t[0].stamp, 1.5);
  EXPECT_TRUE(t[0].T_wc.translation().isApprox(Eigen::Vector3d(1, 2, 3)));
  EXPECT_NEAR(Eigen::AngleAxisd(t[1].T_wc.linear()).angle(), 90.0 / kDegreesPerRadian, 1e-6);
  // Unnormalised quaternions are normalised.
  EXPECT_LT((t[2].T_wc.linear() - Eigen::Matrix3d::Identity()).norm(), 1e-12);
}

TEST(TumTrajectoryFile, MalformedLineThrowsWithLineNumber) {
  TempDir dir;
  const std::string header = "# comment\n1.0 0 0 0 0 0 0 1\n";
  const struct {
    const char* name;
    std::string bad_line;
    const char* expected_fragment;
  } cases[] = {{"few.txt", "2.0 0 0 0 0 0 1", "got 7"},
               {"word.txt", "2.0 0 0 abc 0 0 0 1", "'abc'"},
               {"nan.txt", "2.0 0 0 0 nan 0 0 1", "'nan'"},
               {"suffix.txt", "2.0 0 0 0.5m 0 0 0 1", "'0.5m'"},
               {"zeroq.txt", "2.0 0 0 0 0 0 0 0", "zero norm"},
               {"huge.txt", "2.0 1e308 0 0 0 0 0 1", "'1e308'"}};
  for (const auto& c : cases) {
    const std::string path = dir.file(c.name);
    writeText(path, header + c.bad_line + "\n3.0 0 0 0 0 0 0 1\n");
    const std::string message = readErrorMessage(path);
    EXPECT_NE(message.find("line 3"), std::string::npos) << c.name << ": " << message;
    EXPECT_NE(message.find(path), std::string::npos) << c.name << ": " << message;
    EXPECT_NE(message.find(c.expected_fragment), std::string::npos) << c.name << ": " << message;
  }
  const std::string missing = dir.file("does_not_exist.txt");
  EXPECT_NE(readErrorMessage(missing).find(missing), std::string::npos);
  EXPECT_THROW(writeTumTrajectory(dir.file("no_such_dir/t.txt"), makeTrajectory(2)),
               std::runtime_error);
}

// A stamp given twice is paired twice (with two ground-truth poses): ply_slam_eval refuses it.
TEST(TrajectoryAssociation, FindsTheFirstRepeatedStamp) {
  Trajectory t = makeTrajectory(5);
  EXPECT_FALSE(findRepeatedStamp(t));
  t[3].stamp = t[1].stamp;
  const auto repeated = findRepeatedStamp(t);
  ASSERT_TRUE(repeated);
  EXPECT_EQ(*repeated, std::make_pair(size_t{1}, size_t{3}));
}

// ---------------------------------------------------------------- plot

int countPixels(const cv::Mat& image, const cv::Vec3b& color) {
  int count = 0;
  for (int r = 0; r < image.rows; ++r) {
    for (int c = 0; c < image.cols; ++c) count += image.at<cv::Vec3b>(r, c) == color;
  }
  return count;
}

TEST(TrajectoryPlot, DrawsBothTrajectoriesAndSurvivesDegenerateInput) {
  TempDir dir;
  const Trajectory gt = makeTrajectory(100);
  Trajectory est = gt;
  for (StampedPose& pose : est) pose.T_wc.translation() += Eigen::Vector3d(0.2, -0.1, 0.1);
  writeTrajectoryPlot(dir.file("plot.png"), gt, est, "test plot");
  const cv::Mat image = cv::imread(dir.file("plot.png"));
  ASSERT_FALSE(image.empty());
  EXPECT_EQ(image.cols, 1200);
  EXPECT_EQ(image.rows, 600);
  // Solid line colours: ground truth green, estimate red (BGR).
  EXPECT_GT(countPixels(image, cv::Vec3b(0, 150, 0)), 200);
  EXPECT_GT(countPixels(image, cv::Vec3b(0, 0, 220)), 200);

  EXPECT_NO_THROW(writeTrajectoryPlot(dir.file("empty_gt.png"), {}, est, "no ground truth"));
  EXPECT_NO_THROW(writeTrajectoryPlot(dir.file("single.png"), {gt[0]}, {est[0]}, "one pose"));
  EXPECT_NO_THROW(writeTrajectoryPlot(dir.file("nothing.png"), {}, {}, "nothing"));
  EXPECT_NO_THROW(writeTrajectoryPlot(dir.file("long_title.png"), gt, est,
                                      std::string(300, 'x') + " very long title"));
  for (const char* name : {"empty_gt.png", "single.png", "nothing.png", "long_title.png"}) {
    EXPECT_FALSE(cv::imread(dir.file(name)).empty()) << name;
  }
  EXPECT_THROW(writeTrajectoryPlot(dir.file("no_such_dir/p.png"), gt, est, "x"),
               std::runtime_error);
}

// ---------------------------------------------------------------- real ground truth

TEST(RealGroundTruth, AteOfTransformedCopyOfFr1XyzIsZero) {
  const std::string path =
      test::sharedPath("data/tum/rgbd_dataset_freiburg1_xyz_37/groundtruth.txt");
  PLY_SLAM_REQUIRE_SHARED(path);
  const Trajectory gt = readTumTrajectory(path);
  ASSERT_GT(gt.size(), 1000u);
  const Eigen::Isometry3d T =
      makePose(Eigen::Vector3d(0.1, 0.9, -0.3), 1.2, Eigen::Vector3d(-3.0, 2.0, 0.5));
  const AteResult ate = computeAte(gt, transformed(T, gt));
  EXPECT_EQ(ate.translation.count, gt.size());
  EXPECT_LT(ate.translation.rmse, 1e-9);
  EXPECT_LT(maxAbsDifference(ate.T_gt_est, T.inverse()), 1e-9);
  const RpeResult rpe = computeRpeSeconds(gt, transformed(T, gt), 1.0);
  EXPECT_GT(rpe.translation.count, 1000u);
  EXPECT_LT(rpe.translation.max, 1e-9);
  EXPECT_LT(rpe.rotation.max, 1e-9);

  // Writing and reading back changes the file's 4-decimal values by rounding only.
  TempDir dir;
  writeTumTrajectory(dir.file("gt.txt"), gt);
  EXPECT_LT(computeAte(gt, readTumTrajectory(dir.file("gt.txt"))).translation.max, 1e-6);
}

}  // namespace
}  // namespace ply_slam
