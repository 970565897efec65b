// LocalBundleAdjuster: keyframe poses and points around a new keyframe, on a small map with
// exact observations, so the correction has a known answer.
#include <gtest/gtest.h>

#include <atomic>
#include <memory>
#include <optional>
#include <random>
#include <vector>

#include "ply_slam/map/map.h"
#include "ply_slam/mapping/global_bundle_adjustment.h"
#include "ply_slam/mapping/local_bundle_adjuster.h"
#include "ply_slam/system/system_config.h"
#include "pose_test_helpers.h"

namespace ply_slam {
namespace {

using namespace ::ply_slam::test;

const std::vector<double> kScales{1.0};

// Four keyframes 10 cm apart looking along z at 60 points 2-5 m away, every point seen by
// every keyframe with its exact pixel and depth.
class SmallMap : public testing::Test {
 protected:
  void SetUp() override {
    config_.camera = makeCamera();
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> x(-1.5, 1.5), y(-1.0, 1.0), z(2.0, 5.0);
    for (int k = 0; k < 60; ++k) points_.push_back({x(rng), y(rng), z(rng)});
    for (int f = 0; f < 4; ++f)
      keyframes_.push_back(addKeyFrameSeeingEveryPoint(
          makePose({0.2, 1.0, 0.1}, 1.5 * f, {-0.1 * f, 0.02 * f, 0.0})));
    for (size_t i = 0; i < points_.size(); ++i) {
      auto point = map_.createMapPoint(points_[i], cv::Mat::zeros(1, 32, CV_8U), 0);
      for (const auto& kf : keyframes_) map_.addObservation(*kf, i, point);
    }
  }

  // A keyframe with a keypoint at each point's exact pixel and depth (not linked yet).
  std::shared_ptr<KeyFrame> addKeyFrameSeeingEveryPoint(const Eigen::Isometry3d& T_cw) {
    auto kf = std::make_shared<KeyFrame>();
    kf->T_cw = T_cw;
    map_.addKeyFrame(kf);
    FrameFeatures& features = kf->features;
    features.scales = &kScales;
    for (const Eigen::Vector3d& p : points_) {
      const Eigen::Vector3d c = kf->T_cw * p;
      const Eigen::Vector2d uv = config_.camera.project(c);
      cv::KeyPoint keypoint;
      keypoint.pt = cv::Point2f(static_cast<float>(uv.x()), static_cast<float>(uv.y()));
      features.keypoints.push_back(keypoint);
      features.undistorted.push_back(uv);
      features.rectified.push_back(uv);
      features.depth.push_back(static_cast<float>(c.z()));
    }
    kf->map_points.resize(points_.size());
    return kf;
  }

  SystemConfig config_;
  Map map_;
  std::vector<Eigen::Vector3d> points_;
  std::vector<std::shared_ptr<KeyFrame>> keyframes_;
};

TEST_F(SmallMap, MovedKeyFrameReturnsToItsPose) {
  const Eigen::Isometry3d truth = keyframes_[3]->T_cw;
  keyframes_[3]->T_cw = makePose({1, 0, 0}, 0.5, {0.01, -0.01, 0.02}) * truth;
  const LocalBundleAdjustmentStats stats =
      LocalBundleAdjuster(config_.camera, config_.mapping).adjust(map_, *keyframes_[3]);
  EXPECT_EQ(stats.keyframes, 3);  // keyframe 0 holds the gauge
  EXPECT_EQ(stats.points, 60);
  EXPECT_EQ(stats.outliers_removed, 0);
  EXPECT_LT((keyframes_[3]->T_cw.translation() - truth.translation()).norm(), 1e-4);
  EXPECT_LT(rotationErrorDeg(keyframes_[3]->T_cw, truth), 0.01);
  EXPECT_LT((map_.mapPoints()[0]->position - points_[0]).norm(), 1e-4);
}

TEST_F(SmallMap, AnObservationFarOffIsRemoved) {
  // Keypoint 5 of keyframe 2 moved 40 px: an outlier after adjustment, unlinked from its point.
  keyframes_[2]->features.undistorted[5] += Eigen::Vector2d(40.0, 0.0);
  const LocalBundleAdjustmentStats stats =
      LocalBundleAdjuster(config_.camera, config_.mapping).adjust(map_, *keyframes_[3]);
  EXPECT_EQ(stats.outliers_removed, 1);
  EXPECT_EQ(keyframes_[2]->map_points[5], nullptr);
  // Huber bounds its pull during the solve that finds it (8.9 mm here).
  EXPECT_LT((map_.mapPoints()[5]->position - points_[5]).norm(), 0.02);
}

// The mapping thread solves without the map's lock: what the tracker or the mapper changed in
// between must survive the write-back.
TEST_F(SmallMap, WhatChangedDuringTheSolveIsRespected) {
  keyframes_[2]->features.undistorted[5] += Eigen::Vector2d(40.0, 0.0);  // an outlier, as above
  const LocalBundleAdjuster adjuster(config_.camera, config_.mapping);
  BundleWindow window = adjuster.gatherLocal(*keyframes_[3]);
  adjuster.solve(window);
  // Meanwhile keypoint 5 of keyframe 2 was linked to another landmark, and point 7 was merged
  // away (bad) with its position moved by whoever merged it.
  map_.removeObservation(*keyframes_[2], 5);
  auto other = map_.createMapPoint(points_[5], cv::Mat::zeros(1, 32, CV_8U), 2);
  map_.addObservation(*keyframes_[2], 5, other);
  const auto merged = map_.mapPoints()[7];
  merged->bad = true;
  merged->position = Eigen::Vector3d(9.0, 9.0, 9.0);
  const LocalBundleAdjustmentStats stats = adjuster.apply(map_, window);
  EXPECT_EQ(stats.outliers_removed, 0);  // the outlier's link is gone already
  EXPECT_EQ(keyframes_[2]->map_points[5], other);
  EXPECT_EQ(merged->position, Eigen::Vector3d(9.0, 9.0, 9.0));
  // The rest is written back as usual.
  EXPECT_LT((map_.mapPoints()[0]->position - points_[0]).norm(), 1e-4);
}

TEST_F(SmallMap, GatheringCopiesAndSolvingLeavesTheMapAlone) {
  const Eigen::Isometry3d truth = keyframes_[3]->T_cw;
  keyframes_[3]->T_cw = makePose({1, 0, 0}, 0.5, {0.01, -0.01, 0.02}) * truth;
  const Eigen::Isometry3d moved = keyframes_[3]->T_cw;
  const LocalBundleAdjuster adjuster(config_.camera, config_.mapping);
  BundleWindow window = adjuster.gatherLocal(*keyframes_[3]);
  adjuster.solve(window);
  EXPECT_EQ(keyframes_[3]->T_cw.matrix(), moved.matrix());  // not written yet
  adjuster.apply(map_, window);
  EXPECT_LT((keyframes_[3]->T_cw.translation() - truth.translation()).norm(), 1e-4);
}

TEST_F(SmallMap, ASolveAskedToStopReportsIt) {
  const LocalBundleAdjuster adjuster(config_.camera, config_.mapping);
  BundleWindow window = adjuster.gatherAll(map_, 10);
  std::atomic<bool> abandon{true};
  EXPECT_FALSE(adjuster.solve(window, &abandon));
  abandon = false;
  EXPECT_TRUE(adjuster.solve(window, &abandon));
}

// On the mapping thread the whole map's copy lets go of the lock between pieces; a keyframe
// the tracker makes meanwhile sees the window's landmarks but stays out of it.
TEST_F(SmallMap, AWholeMapGatheredInPiecesLeavesOutKeyFramesMadeMeanwhile) {
  const Eigen::Isometry3d truth = keyframes_[3]->T_cw;
  keyframes_[3]->T_cw = makePose({1, 0, 0}, 0.5, {0.01, -0.01, 0.02}) * truth;
  const LocalBundleAdjuster adjuster(config_.camera, config_.mapping);
  const BundleWindow whole = adjuster.gatherAll(map_, 10);

  int calls = 0;
  std::shared_ptr<KeyFrame> made;
  BundleWindow pieces = adjuster.gatherAll(map_, 10, [&] {
    if (++calls != 2) return;  // after the second keyframe's landmarks
    made = addKeyFrameSeeingEveryPoint(makePose({0, 1, 0}, 2.0, {-0.2, 0.0, 0.0}) * truth);
    for (size_t i = 0; i < points_.size(); ++i) map_.addObservation(*made, i, map_.mapPoints()[i]);
  });
  EXPECT_EQ(calls, 4 + 60);  // after each keyframe's landmarks and each landmark's observations
  ASSERT_TRUE(made);
  EXPECT_EQ(map_.mapPoints()[0]->observations(), 5);
  ASSERT_EQ(pieces.poses.size(), whole.poses.size());
  for (size_t i = 0; i < whole.poses.size(); ++i)
    EXPECT_EQ(pieces.poses[i].keyframe, whole.poses[i].keyframe);
  ASSERT_EQ(pieces.observations.size(), whole.observations.size());
  for (size_t i = 0; i < whole.observations.size(); ++i) {
    EXPECT_EQ(pieces.observations[i].pose, whole.observations[i].pose);
    EXPECT_EQ(pieces.observations[i].point, whole.observations[i].point);
  }
  EXPECT_EQ(pieces.points, whole.points);
  adjuster.solve(pieces);
  adjuster.apply(map_, pieces);
  EXPECT_LT((keyframes_[3]->T_cw.translation() - truth.translation()).norm(), 1e-4);
  EXPECT_EQ(map_.mapPoints()[0]->observations(), 5);  // the new keyframe's links stay
}

// The global BA after a loop runs beside the mapping side: a keyframe made meanwhile, and the
// landmark it made, must move with the keyframe it hangs from.
TEST_F(SmallMap, GlobalAdjustmentCarriesAlongWhatWasMadeMeanwhile) {
  const Eigen::Isometry3d truth = keyframes_[3]->T_cw;
  keyframes_[3]->T_cw = makePose({1, 0, 0}, 0.5, {0.01, -0.01, 0.02}) * truth;
  const LocalBundleAdjuster adjuster(config_.camera, config_.mapping);
  GlobalBundleAdjustment global(adjuster);
  global.start(adjuster.gatherAll(map_, 10));
  global.wait();
  // Made while it was solving: 20 cm beside keyframe 3, with a landmark of its own.
  auto made = std::make_shared<KeyFrame>();
  made->T_cw = makePose({0, 1, 0}, 2.0, {-0.2, 0.0, 0.0}) * keyframes_[3]->T_cw;
  made->parent = keyframes_[3].get();
  map_.addKeyFrame(made);
  const Eigen::Vector3d seen(0.1, 0.2, 3.0);  // in the new keyframe's frame
  auto point = map_.createMapPoint(made->T_wc() * seen, cv::Mat::zeros(1, 32, CV_8U), made->id);
  const Eigen::Isometry3d relative = keyframes_[3]->T_wc().inverse() * made->T_wc();
  const Eigen::Isometry3d made_before = made->T_wc();

  std::optional<BundleWindow> solved = global.takeSolved();
  ASSERT_TRUE(solved);
  const Eigen::Isometry3d moved = global.writeBack(map_, *solved);
  EXPECT_LT((keyframes_[3]->T_cw.translation() - truth.translation()).norm(), 1e-4);
  const Eigen::Isometry3d now = keyframes_[3]->T_wc().inverse() * made->T_wc();
  EXPECT_TRUE(now.isApprox(relative, 1e-9));
  EXPECT_LT((made->T_cw * point->position - seen).norm(), 1e-9);
  EXPECT_TRUE((moved * made_before).isApprox(made->T_wc(), 1e-9));  // the newest's move
  EXPECT_GT(moved.translation().norm(), 0.01);                      // the new keyframe did move
  EXPECT_FALSE(global.takeSolved());                                // taken once
  EXPECT_EQ(global.started(), 1);
  EXPECT_EQ(global.abandoned(), 0);
}

}  // namespace
}  // namespace ply_slam
