// Tracking lost on featureless frames is regained by relocalisation against the keyframes,
// at the right place (checked against ground truth).
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "default_vocabularies.h"
#include "ply_slam/common/config.h"
#include "ply_slam/eval/trajectory_metrics.h"
#include "ply_slam/features/orb_extractor.h"
#include "ply_slam/io/tum_sequence.h"
#include "ply_slam/mapping/landmark_creator.h"
#include "ply_slam/system/system.h"
#include "ply_slam/tracking/tracker.h"
#include "shared_data.h"

namespace ply_slam {
namespace {

// Tracks fr1_xyz_37 with the lens covered for frames 10..14.
void expectRecoveryAfterBlankFrames(const std::string& folder, const SystemConfig& config) {
  const TumSequence sequence(folder);
  ASSERT_GE(sequence.size(), 30u);
  System system(config);

  for (size_t i = 0; i < 10; ++i) {
    const FrameResult r = system.process(sequence.load(i, config.camera.depth_factor));
    ASSERT_EQ(r.tracking.state, TrackingState::kOk) << "frame " << i;
  }
  // The lens is covered for frames 10..14: no features, tracking is lost.
  for (size_t i = 10; i < 15; ++i) {
    RgbdImages blank = sequence.load(i, config.camera.depth_factor);
    blank.rgb.setTo(cv::Scalar(0, 0, 0));
    EXPECT_EQ(system.process(blank).tracking.state, TrackingState::kLost) << "frame " << i;
  }
  // Uncovered, about 15 frames (0.1 m) further on: found again against the keyframes.
  const FrameResult back = system.process(sequence.load(15, config.camera.depth_factor));
  EXPECT_EQ(back.tracking.state, TrackingState::kOk);
  EXPECT_EQ(back.tracking.method, "reloc");
  for (size_t i = 16; i < sequence.size(); ++i)
    EXPECT_EQ(system.process(sequence.load(i, config.camera.depth_factor)).tracking.state,
              TrackingState::kOk)
        << "frame " << i;

  // The trajectory has no blank frames and stays accurate across the gap.
  EXPECT_EQ(system.cameraTrajectory().size(), sequence.size() - 5);
  const AteResult ate = computeAte(sequence.groundTruth(), system.cameraTrajectory());
  EXPECT_LT(ate.translation.rmse, 0.01);
}

SystemConfig fr1Config() {
  return loadConfig(std::string(PLY_SLAM_SOURCE_DIR) + "/config/tum_fr1.yaml");
}

TEST(Relocalisation, RecoversAfterBlankFrames) {
  const std::string folder = test::sharedPath("data/tum/rgbd_dataset_freiburg1_xyz_37");
  PLY_SLAM_REQUIRE_SHARED(folder);
  expectRecoveryAfterBlankFrames(folder, fr1Config());
}

// With loop.enabled the keyframes to try come from the place-recognition database.
TEST(Relocalisation, RecoversThroughThePlaceDatabase) {
  const std::string folder = test::sharedPath("data/tum/rgbd_dataset_freiburg1_xyz_37");
  PLY_SLAM_REQUIRE_SHARED(folder);
  PLY_SLAM_REQUIRE_VOCABULARY(defaultVocabularyPath(DescriptorKind::kOrb));
  PLY_SLAM_REQUIRE_VOCABULARY(defaultVocabularyPath(DescriptorKind::kLbd));
  SystemConfig config = fr1Config();
  config.loop.enabled = true;
  expectRecoveryAfterBlankFrames(folder, config);
}

// A database that offers no keyframe: relocalisation has nothing to try and stays lost, so the
// tracker really relocalises through the database's candidates and not around them.
TEST(Relocalisation, TriesOnlyTheDatabasesCandidates) {
  const std::string folder = test::sharedPath("data/tum/rgbd_dataset_freiburg1_xyz_37");
  PLY_SLAM_REQUIRE_SHARED(folder);
  const SystemConfig config = fr1Config();
  const TumSequence sequence(folder);
  Map map;
  OrbExtractor extractor(config.orb);
  LandmarkCreator mapping(config.camera, config.tracking.max_point_depth, config.lines, map);
  Tracker tracker(config.camera, config.tracking, config.orb, config.lines, map, mapping);
  long offered = 0;
  tracker.setPlaceCandidates([&](const Frame&) {
    ++offered;
    return std::vector<long>{};
  });
  const auto frame = [&](size_t i, bool blank) {
    RgbdImages images = sequence.load(i, config.camera.depth_factor);
    if (blank) images.rgb.setTo(cv::Scalar(0, 0, 0));
    cv::Mat gray;
    cv::cvtColor(images.rgb, gray, cv::COLOR_BGR2GRAY);
    return Frame(static_cast<long>(i), images.stamp,
                 FrameFeatures::extract(gray, images.depth, config.camera, extractor));
  };
  for (size_t i = 0; i < 5; ++i) {
    Frame f = frame(i, false);
    ASSERT_EQ(tracker.track(f).state, TrackingState::kOk) << "frame " << i;
  }
  Frame blank = frame(5, true);
  EXPECT_EQ(tracker.track(blank).state, TrackingState::kLost);
  Frame back = frame(6, false);
  EXPECT_EQ(tracker.track(back).state, TrackingState::kLost);
  EXPECT_GE(offered, 1);
}

// A 1-pixel search window makes the motion model miss now and then (about 6 of 32 frames);
// PnP against the last frame's local map then keeps tracking. Before the local map's
// deduplication became the tracker's own, that map came back nearly empty (its landmarks were
// still marked as taken by the last frame) and such a frame was lost.
TEST(Relocalisation, PnpAgainstTheLocalMapCatchesWhatTheMotionModelMisses) {
  const std::string folder = test::sharedPath("data/tum/rgbd_dataset_freiburg1_xyz_37");
  PLY_SLAM_REQUIRE_SHARED(folder);
  SystemConfig config = fr1Config();
  config.tracking.search_radius_px = 1;
  const TumSequence sequence(folder);
  System system(config);
  int by_pnp = 0;
  for (size_t i = 0; i < sequence.size(); ++i) {
    const FrameResult r = system.process(sequence.load(i, config.camera.depth_factor));
    EXPECT_EQ(r.tracking.state, TrackingState::kOk) << "frame " << i << " " << r.tracking.method;
    by_pnp += r.tracking.method == "pnp";
  }
  EXPECT_GE(by_pnp, 3);
  EXPECT_EQ(system.cameraTrajectory().size(), sequence.size());
  EXPECT_LT(computeAte(sequence.groundTruth(), system.cameraTrajectory()).translation.rmse, 0.01);
}

}  // namespace
}  // namespace ply_slam
