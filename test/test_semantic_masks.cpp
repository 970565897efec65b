// Instance masks from a folder, and the system leaving out features on moving objects.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

#include "ply_slam/eval/trajectory_metrics.h"
#include "ply_slam/io/tum_sequence.h"
#include "ply_slam/semantic/mask_folder_segmenter.h"
#include "ply_slam/synth/synthetic_sequence.h"
#include "ply_slam/synth/synthetic_sequence_writer.h"
#include "ply_slam/system/system.h"
#include "ply_slam/system/system_config.h"
#include "shared_data.h"

namespace fs = std::filesystem;

namespace ply_slam {
namespace {

const char* const kWalkers = "data/dynamic/fr1_rpy_150_349_walkers";

// visible_mask_px of instance `id` at the first stamp of instance_poses.txt.
long visiblePixels(const std::string& folder, int id) {
  std::ifstream in(folder + "/instance_poses.txt");
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream f(line);
    double stamp, foot[3], normal[3];
    int instance, sprite, mirrored;
    long pixels;
    f >> stamp >> instance >> foot[0] >> foot[1] >> foot[2] >> normal[0] >> normal[1] >>
        normal[2] >> sprite >> mirrored >> pixels;
    if (instance == id) return pixels;
  }
  return -1;
}

TEST(MaskFolderSegmenter, ReadsTheWalkersMasks) {
  const std::string folder = test::sharedPath(kWalkers);
  PLY_SLAM_REQUIRE_SHARED(folder);
  const TumSequence sequence(folder);
  MaskFolderSegmenter segmenter(folder);
  const auto instances = segmenter.segment(sequence.load(0, 5000.0));
  ASSERT_EQ(instances.size(), 2u);
  for (const auto& instance : instances) {
    EXPECT_EQ(instance.class_name, "person");
    EXPECT_EQ(cv::countNonZero(instance.mask), visiblePixels(folder, instance.id))
        << "instance " << instance.id;
  }
}

TEST(MaskFolderSegmenter, MissingFilesAreNamed) {
  const fs::path dir =
      fs::temp_directory_path() / ("ply_slam_test_masks_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir / "masks");
  try {
    MaskFolderSegmenter segmenter(dir.string());
    FAIL() << "no instances.txt accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("instances.txt"), std::string::npos) << e.what();
  }
  std::ofstream(dir / "instances.txt") << "# id class\n1 person\n";
  MaskFolderSegmenter segmenter(dir.string());
  RgbdImages images;
  images.stamp = 12.5;
  images.rgb = cv::Mat::zeros(48, 64, CV_8UC3);
  try {
    segmenter.segment(images);
    FAIL() << "missing mask accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("12.500000.png"), std::string::npos) << e.what();
  }
  cv::imwrite((dir / "masks" / "12.500000.png").string(), cv::Mat::zeros(48, 64, CV_16UC1));
  EXPECT_THROW(segmenter.segment(images), std::runtime_error);  // 16-bit ids
  fs::remove(dir / "masks" / "12.500000.png");
  ASSERT_EQ(::mkfifo((dir / "masks" / "12.500000.png").c_str(), 0600), 0);
  try {
    segmenter.segment(images);  // blocked for ever before (issue #53)
    FAIL() << "a named pipe as a mask accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("12.500000.png: is a named pipe"), std::string::npos)
        << e.what();
  }
  fs::remove(dir / "instances.txt");
  ASSERT_EQ(::mkfifo((dir / "instances.txt").c_str(), 0600), 0);
  EXPECT_THROW(MaskFolderSegmenter again(dir.string()), std::runtime_error);
  fs::remove_all(dir);
}

// A synthetic office with two people walking: with their masks the trajectory stays exact,
// and the features on them are counted as dropped.
TEST(DynamicFeatures, WalkersMaskedOutOnSyntheticOffice) {
  SynthOptions options;
  options.walkers = 2;
  options.frames = 90;
  const fs::path dir =
      fs::temp_directory_path() / ("ply_slam_test_walkers_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  writeSyntheticSequence(SyntheticSequence(options), dir.string());

  const SystemConfig config = loadConfig((dir / "camera.yaml").string());
  const TumSequence sequence(dir.string());
  MaskFolderSegmenter segmenter(dir.string());
  System system(config);
  size_t dropped = 0;
  for (size_t i = 0; i < sequence.size(); ++i) {
    const RgbdImages images = sequence.load(i, config.camera.depth_factor);
    const FrameResult r = system.process(images, segmenter.segment(images));
    EXPECT_EQ(r.tracking.state, TrackingState::kOk) << "frame " << i;
    dropped += r.dynamic_features;
  }
  EXPECT_GT(dropped, 1000u);
  const double ate = computeAte(sequence.groundTruth(), system.cameraTrajectory()).translation.rmse;
  EXPECT_LT(ate, 0.005);
  fs::remove_all(dir);
}

TEST(DynamicFeatures, StaticClassesAreKept) {
  const std::string folder = test::sharedPath(kWalkers);
  PLY_SLAM_REQUIRE_SHARED(folder);
  const SystemConfig config = loadConfig(std::string(PLY_SLAM_SOURCE_DIR) + "/config/tum_fr1.yaml");
  const TumSequence sequence(folder);
  MaskFolderSegmenter segmenter(folder);
  const RgbdImages images = sequence.load(0, config.camera.depth_factor);
  auto instances = segmenter.segment(images);
  System as_people(config);
  EXPECT_GT(as_people.process(images, instances).dynamic_features, 20u);
  for (auto& instance : instances) instance.class_name = "chair";  // passive: kept here
  System as_chairs(config);
  EXPECT_EQ(as_chairs.process(images, instances).dynamic_features, 0u);
}

}  // namespace
}  // namespace ply_slam
