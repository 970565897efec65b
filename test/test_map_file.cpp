// Map files (map module): a saved map loads again as it was, and a missing,
// truncated, corrupted, other-version or other-vocabulary file is refused with an error naming
// the file and the fault, the system left unchanged.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>

#include "default_vocabularies.h"
#include "ply_slam/io/byte_reader.h"
#include "ply_slam/io/fnv1a.h"
#include "ply_slam/io/tum_sequence.h"
#include "ply_slam/loop/binary_vocabulary.h"
#include "ply_slam/system/system.h"
#include "ply_slam/system/system_config.h"
#include "shared_data.h"
#include "temp_dir.h"

namespace ply_slam {
namespace {

namespace fs = std::filesystem;

SystemConfig loopConfig() {
  SystemConfig config = loadConfig(std::string(PLY_SLAM_SOURCE_DIR) + "/config/tum_fr1.yaml");
  config.loop.enabled = true;
  return config;
}

std::vector<uint8_t> fileBytes(const fs::path& path) { return *readFileBytes(path.string()); }

void writeBytes(const fs::path& path, const std::vector<uint8_t>& bytes) {
  fs::create_directories(path.parent_path());
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(bytes.data()),
            static_cast<std::streamsize>(bytes.size()));
}

std::map<long, long> idsOf(const KeyFrame& kf) {  // keypoint -> point id
  std::map<long, long> ids;
  for (size_t i = 0; i < kf.map_points.size(); ++i)
    if (kf.map_points[i] && !kf.map_points[i]->bad)
      ids[static_cast<long>(i)] = kf.map_points[i]->id;
  return ids;
}

std::map<long, int> covisibilityOf(const KeyFrame& kf) {
  std::map<long, int> ids;
  for (const auto& [other, shared] : kf.covisibility) ids[other->id] = shared;
  return ids;
}

class MapFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const std::string folder = test::sharedPath("data/tum/rgbd_dataset_freiburg1_xyz_37");
    PLY_SLAM_REQUIRE_SHARED(folder);
    PLY_SLAM_REQUIRE_VOCABULARY(defaultVocabularyPath(DescriptorKind::kOrb));
    PLY_SLAM_REQUIRE_VOCABULARY(defaultVocabularyPath(DescriptorKind::kLbd));
    const TumSequence sequence(folder);
    mapped_ = std::make_unique<System>(loopConfig());
    for (size_t i = 0; i < 20; ++i)
      mapped_->process(sequence.load(i, mapped_->config().camera.depth_factor));
    mapped_->saveMap(saved());
  }

  std::string saved() const { return dir_.file("saved"); }
  fs::path savedFile() const { return fs::path(saved()) / System::kMapFileName; }

  // A copy of the saved map with its bytes changed by `change`, in folder `name`.
  std::string alteredCopy(const std::string& name,
                          const std::function<void(std::vector<uint8_t>&)>& change) const {
    std::vector<uint8_t> bytes = fileBytes(savedFile());
    change(bytes);
    writeBytes(fs::path(dir_.file(name)) / System::kMapFileName, bytes);
    return dir_.file(name);
  }

  // Loading `folder` fails with a message naming its file and containing `fault`; the system
  // is left as it was: empty, and it still takes the good map afterwards.
  void expectRefused(const std::string& folder, const std::string& fault,
                     const SystemConfig& config = loopConfig()) {
    System system(config);
    try {
      system.loadMap(folder);
      ADD_FAILURE() << "loaded " << folder;
    } catch (const std::runtime_error& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find((fs::path(folder) / System::kMapFileName).string()), std::string::npos)
          << message;
      EXPECT_NE(message.find(fault), std::string::npos) << message;
    }
    EXPECT_EQ(system.map().numKeyFrames(), 0u);
    EXPECT_EQ(system.map().numMapPoints(), 0u);
  }

  TempDir dir_;
  std::unique_ptr<System> mapped_;
};

TEST_F(MapFileTest, RoundTripKeepsKeyFramesLandmarksAndLinks) {
  System loaded(loopConfig());
  loaded.loadMap(saved());
  const auto before = mapped_->map().keyFrames();
  const auto after = loaded.map().keyFrames();
  ASSERT_GE(before.size(), 3u);
  ASSERT_EQ(after.size(), before.size());
  for (size_t k = 0; k < before.size(); ++k) {
    const KeyFrame &a = *before[k], &b = *after[k];
    EXPECT_EQ(b.id, a.id);
    EXPECT_EQ(b.frame_id, a.frame_id);
    EXPECT_EQ(b.stamp, a.stamp);
    EXPECT_TRUE(b.T_cw.matrix() == a.T_cw.matrix()) << "keyframe " << a.id;
    ASSERT_EQ(b.features.size(), a.features.size());
    EXPECT_EQ(cv::norm(a.features.descriptors, b.features.descriptors, cv::NORM_HAMMING), 0.0);
    EXPECT_EQ(b.features.undistorted, a.features.undistorted);
    EXPECT_EQ(b.features.depth, a.features.depth);
    EXPECT_EQ(idsOf(b), idsOf(a)) << "keyframe " << a.id;
    EXPECT_EQ(covisibilityOf(b), covisibilityOf(a)) << "keyframe " << a.id;
    EXPECT_EQ(b.parent ? b.parent->id : -1, a.parent ? a.parent->id : -1);
  }
  EXPECT_EQ(after.front()->parent, nullptr);  // the root
  ASSERT_EQ(loaded.map().numMapPoints(), mapped_->map().numMapPoints());
  const auto points = loaded.map().mapPoints();
  const auto originals = mapped_->map().mapPoints();
  for (size_t i = 0; i < points.size(); ++i) {
    EXPECT_EQ(points[i]->id, originals[i]->id);
    EXPECT_TRUE(points[i]->position == originals[i]->position);
    EXPECT_EQ(points[i]->observations(), originals[i]->observations());
  }
  // Saved again, the loaded map gives the same bytes: nothing was lost or changed on the way.
  loaded.saveMap(dir_.file("again"));
  EXPECT_EQ(fileBytes(fs::path(dir_.file("again")) / System::kMapFileName), fileBytes(savedFile()));
}

TEST_F(MapFileTest, MissingFileIsNamed) {
  expectRefused(dir_.file("nothing_here"), "cannot be opened");
}

// A named pipe blocked the load for ever; a directory was "basic_filebuf::underflow" without
// the file's name (issue #53).
TEST_F(MapFileTest, SpecialFilesAreRefusedNamingThem) {
  const fs::path fifo_folder = dir_.file("fifo"), dir_folder = dir_.file("dir");
  fs::create_directories(fifo_folder);
  fs::create_directories(dir_folder / System::kMapFileName);
  ASSERT_EQ(::mkfifo((fifo_folder / System::kMapFileName).c_str(), 0600), 0);
  expectRefused(fifo_folder.string(), "named pipe");
  expectRefused(dir_folder.string(), "is a directory");
}

TEST_F(MapFileTest, TruncatedFileIsRefused) {
  expectRefused(alteredCopy("cut", [](auto& b) { b.resize(b.size() - 1000); }), "truncated");
  expectRefused(alteredCopy("head", [](auto& b) { b.resize(12); }), "truncated");
}

TEST_F(MapFileTest, FlippedByteFailsTheChecksum) {
  expectRefused(alteredCopy("flipped", [](auto& b) { b[b.size() / 2] ^= 0x10; }),
                "checksum mismatch");
}

// A payload cut short with a checksum that fits it (a writer's bug, not damage): the records
// do not add up, and the reader says so instead of reading past them.
TEST_F(MapFileTest, ContentThatDoesNotAddUpIsRefused) {
  const std::string folder = alteredCopy("short", [](std::vector<uint8_t>& b) {
    constexpr size_t kHeader = 20, kChecksum = 8, kCut = 4;
    b.erase(b.end() - kChecksum - kCut, b.end());
    const uint64_t payload = b.size() - kHeader;
    for (int i = 0; i < 8; ++i) b[12 + i] = static_cast<uint8_t>(payload >> (8 * i));
    const uint64_t sum = fnv1a64(b.data(), b.size());
    for (int i = 0; i < 8; ++i) b.push_back(static_cast<uint8_t>(sum >> (8 * i)));
  });
  expectRefused(folder, "inconsistent content");
}

TEST_F(MapFileTest, OtherVersionIsRefused) {
  expectRefused(alteredCopy("v2", [](auto& b) { b[8] = 2; }), "format version 2");
}

TEST_F(MapFileTest, OtherVocabularyIsRefusedAndNamed) {
  // The default ORB vocabulary with one idf weight changed: same name and words, other content.
  VocabularyData data =
      BinaryVocabulary::load(defaultVocabularyPath(DescriptorKind::kOrb), DescriptorKind::kOrb)
          .data();
  data.idf[0] += 1.0;
  BinaryVocabulary(data).save(dir_.file("other_orb.voc"));
  SystemConfig config = loopConfig();
  config.loop.orb_vocabulary = dir_.file("other_orb.voc");
  expectRefused(saved(), "built with the ORB vocabulary orb_k10_l5.voc", config);
  expectRefused(saved(), "this system uses other_orb.voc", config);
}

TEST_F(MapFileTest, OtherCameraIsRefused) {
  SystemConfig config = loopConfig();
  config.camera.fx += 1.0;
  expectRefused(saved(), "another camera", config);
}

// A checksum that holds over numbers no map has (issue #53: a NaN keyframe pose loaded, every
// frame tracked as NaN, "lost 0"): refused as a config would be, naming the item.
TEST_F(MapFileTest, ValuesNoMapHasAreRefusedNamingTheItem) {
  const auto keyframe = mapped_->map().keyFrames()[1];
  const auto point = mapped_->map().mapPoints()[3];
  const Eigen::Isometry3d pose = keyframe->T_cw;
  const Eigen::Vector3d position = point->position;
  auto savedWith = [&](const std::string& name, const std::function<void()>& change) {
    keyframe->T_cw = pose;
    point->position = position;
    change();
    mapped_->saveMap(dir_.file(name));
    return dir_.file(name);
  };
  const std::string kf = "keyframe " + std::to_string(keyframe->id) + " ";
  expectRefused(savedWith("nan_pose", [&] { keyframe->T_cw(0, 3) = std::nan(""); }),
                kf + "has a pose that is not finite");
  expectRefused(savedWith("inf_rotation", [&] { keyframe->T_cw(1, 1) = HUGE_VAL; }),
                kf + "has a pose that is not finite");
  expectRefused(savedWith("scaled", [&] { keyframe->T_cw.linear() *= 1.01; }),
                kf + "has a rotation that is not a rotation matrix");
  expectRefused(savedWith("mirrored", [&] { keyframe->T_cw.linear().col(0) *= -1.0; }),
                kf + "has a rotation that is not a rotation matrix");
  expectRefused(savedWith("far", [&] { keyframe->T_cw(2, 3) = 1e12; }),
                kf + "has a position beyond");
  expectRefused(savedWith("nan_point", [&] { point->position.y() = std::nan(""); }),
                "point " + std::to_string(point->id) + " has a position");
  expectRefused(savedWith("far_point", [&] { point->position.x() = -1e10; }),
                "point " + std::to_string(point->id) + " has a position beyond");
  // Back as it was, it loads.
  System system(loopConfig());
  EXPECT_NO_THROW(system.loadMap(savedWith("good", [] {})));
}

// Both sides of a refused camera differ in what they print (they printed alike at 6 digits).
TEST_F(MapFileTest, AnotherCameraPrintsEveryDigit) {
  SystemConfig config = loopConfig();
  config.camera.fx = std::nextafter(config.camera.fx, 1e9);
  expectRefused(saved(), "fx fy cx cy 517.3 ", config);
  expectRefused(saved(), "(this system: 517.3000000000001 ", config);
}

TEST_F(MapFileTest, LoadingAfterTheFirstFrameIsAnError) {
  const TumSequence sequence(test::sharedPath("data/tum/rgbd_dataset_freiburg1_xyz_37"));
  System system(loopConfig());
  system.process(sequence.load(0, system.config().camera.depth_factor));
  EXPECT_THROW(system.loadMap(saved()), std::logic_error);
}

}  // namespace
}  // namespace ply_slam
