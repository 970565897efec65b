// Tracking lost on featureless frames is regained by relocalisation against the keyframes,
// at the right place (checked against ground truth).
#include <gtest/gtest.h>

#include "ply_slam/common/config.h"
#include "ply_slam/eval/trajectory_metrics.h"
#include "ply_slam/io/tum_sequence.h"
#include "ply_slam/system/system.h"
#include "shared_data.h"

namespace ply_slam {
namespace {

TEST(Relocalisation, RecoversAfterBlankFrames) {
  const std::string folder = test::sharedPath("data/tum/rgbd_dataset_freiburg1_xyz_37");
  PLY_SLAM_REQUIRE_SHARED(folder);
  const SystemConfig config = loadConfig(std::string(PLY_SLAM_SOURCE_DIR) + "/config/tum_fr1.yaml");
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

}  // namespace
}  // namespace ply_slam

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
