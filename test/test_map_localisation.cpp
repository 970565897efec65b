// Localisation in a loaded map: map the first half of fr1_rpy_150_349, save it,
// load it into a new System and run the second half: relocalised within 10 frames, no pose
// before, and the poses in the saved map's frame. That frame is checked with the ground-truth
// alignment of the mapping run, not with a fit of its own: a free fit would hide an offset.
#include <gtest/gtest.h>

#include <iostream>
#include <opencv2/core.hpp>

#include "default_vocabularies.h"
#include "map_equality.h"
#include "ply_slam/eval/trajectory_metrics.h"
#include "ply_slam/io/tum_sequence.h"
#include "ply_slam/system/system.h"
#include "ply_slam/system/system_config.h"
#include "shared_data.h"
#include "temp_dir.h"

namespace ply_slam {
namespace {

constexpr size_t kMappedFrames = 100;  // of 199; the rest is run in the loaded map

SystemConfig loopConfig() {
  SystemConfig config = loadConfig(std::string(PLY_SLAM_SOURCE_DIR) + "/config/tum_fr1.yaml");
  config.loop.enabled = true;
  return config;
}

struct LoadedRun {
  Trajectory trajectory;
  long first_tracked = -1;   // frames of the loaded run before the first tracked one
  std::string first_method;  // how that frame's pose was found
  size_t tracked = 0;
  size_t keyframes_after = 0, keyframes_loaded = 0;
  long last_loaded_id = -1, min_new_keyframe_id = -1;
};

// The frames after the mapped ones, the first `blank` of them black (no mapped view).
LoadedRun runInLoadedMap(const TumSequence& sequence, const std::string& map_folder,
                         bool localisation_only, size_t blank = 0,
                         MappingMode mode = MappingMode::kInline) {
  System system(loopConfig(), mode);
  system.loadMap(map_folder, localisation_only);
  LoadedRun run;
  run.keyframes_loaded = system.map().numKeyFrames();
  run.last_loaded_id = system.map().keyFrames().back()->id;
  for (size_t i = kMappedFrames; i < sequence.size(); ++i) {
    RgbdImages images = sequence.load(i, system.config().camera.depth_factor);
    if (i < kMappedFrames + blank) images.rgb.setTo(cv::Scalar::all(0));
    const FrameResult r = system.process(images);
    const bool ok = r.tracking.state == TrackingState::kOk;
    if (ok && run.first_tracked < 0) {
      run.first_tracked = static_cast<long>(i - kMappedFrames);
      run.first_method = r.tracking.method;
    }
    // Lost until relocalised: never a new map started where the camera happens to be.
    if (run.first_tracked < 0) {
      EXPECT_EQ(r.tracking.state, TrackingState::kLost) << "frame " << i;
    }
    if (r.tracking.new_keyframe && run.min_new_keyframe_id < 0)
      run.min_new_keyframe_id = r.tracking.new_keyframe->id;
    run.tracked += ok;
  }
  run.trajectory = system.cameraTrajectory();
  run.keyframes_after = system.map().numKeyFrames();
  return run;
}

class MapLocalisationTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const std::string folder = test::sharedPath("data/tum/rgbd_dataset_freiburg1_rpy_150_349");
    PLY_SLAM_REQUIRE_SHARED(folder);
    PLY_SLAM_REQUIRE_VOCABULARY(defaultVocabularyPath(DescriptorKind::kOrb));
    PLY_SLAM_REQUIRE_VOCABULARY(defaultVocabularyPath(DescriptorKind::kLbd));
    sequence_ = std::make_unique<TumSequence>(folder);
    ASSERT_GT(sequence_->size(), kMappedFrames + 50);
    System mapping(loopConfig());
    for (size_t i = 0; i < kMappedFrames; ++i)
      mapping.process(sequence_->load(i, mapping.config().camera.depth_factor));
    mapped_ = mapping.cameraTrajectory();
    mapping_ate_ = computeAte(sequence_->groundTruth(), mapped_);
    mapping.saveMap(dir_.path().string());
  }

  TempDir dir_;
  std::unique_ptr<TumSequence> sequence_;
  Trajectory mapped_;
  AteResult mapping_ate_;
};

TEST_F(MapLocalisationTest, RelocalisesAndTracksInTheSavedMapsFrame) {
  // The first 3 frames are black: nothing to relocalise on, so no pose. Frame 103 is the first
  // that sees a mapped view (the mapped frames end at 99).
  constexpr long kBlank = 3;
  const LoadedRun run = runInLoadedMap(*sequence_, dir_.path().string(), true, kBlank);
  ASSERT_GE(run.first_tracked, 0) << "never relocalised";
  EXPECT_GE(run.first_tracked, kBlank);
  EXPECT_LE(run.first_tracked, kBlank + 10);
  EXPECT_EQ(run.first_method, "reloc");
  // No pose before the relocalisation: the trajectory holds tracked frames only, all after it.
  EXPECT_EQ(run.trajectory.size(), run.tracked);
  EXPECT_GE(run.trajectory.front().stamp, sequence_->record(kMappedFrames + kBlank).rgb_stamp);
  EXPECT_GE(run.tracked, (sequence_->size() - kMappedFrames) * 9 / 10);
  EXPECT_EQ(run.keyframes_after, run.keyframes_loaded);  // localisation only: no keyframes
  const AteResult in_map =
      computeAteInFrame(sequence_->groundTruth(), run.trajectory, mapping_ate_.T_gt_est);
  std::cout << "mapping run ATE " << mapping_ate_.translation.rmse << " m ("
            << mapping_ate_.translation.count << " frames); loaded run: first tracked after "
            << run.first_tracked << " frames, " << run.tracked
            << " tracked, ATE in the map's frame " << in_map.translation.rmse << " m ("
            << in_map.translation.count << " frames)\n";
  EXPECT_LE(in_map.translation.rmse, 1.5 * mapping_ate_.translation.rmse);
}

TEST_F(MapLocalisationTest, ExtendsTheMapWhenAsked) {
  const LoadedRun run = runInLoadedMap(*sequence_, dir_.path().string(), false);
  ASSERT_GE(run.first_tracked, 0) << "never relocalised";
  EXPECT_GT(run.keyframes_after, run.keyframes_loaded);
  // New keyframes continue the ids after the loaded ones.
  EXPECT_GT(run.min_new_keyframe_id, run.last_loaded_id);
  const AteResult in_map =
      computeAteInFrame(sequence_->groundTruth(), run.trajectory, mapping_ate_.T_gt_est);
  std::cout << "extending: ATE in the map's frame " << in_map.translation.rmse << " m, "
            << run.keyframes_after - run.keyframes_loaded << " keyframes added\n";
  EXPECT_LE(in_map.translation.rmse, 1.5 * mapping_ate_.translation.rmse);
}

// ply_slam_tum's way: the tracker in a copy of the loaded map, the mapping side in the map.
TEST_F(MapLocalisationTest, ExtendsTheMapTheSameWithTheTrackerInACopy) {
  const LoadedRun one_map = runInLoadedMap(*sequence_, dir_.path().string(), false);
  const LoadedRun split =
      runInLoadedMap(*sequence_, dir_.path().string(), false, 0, MappingMode::kSplit);
  EXPECT_GT(split.keyframes_after, split.keyframes_loaded);
  EXPECT_EQ(split.keyframes_after, one_map.keyframes_after);
  test::expectSameTrajectory(split.trajectory, one_map.trajectory);
}

}  // namespace
}  // namespace ply_slam
