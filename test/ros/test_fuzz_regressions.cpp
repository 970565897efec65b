// Inputs the fuzzers (fuzz/, scripts/fuzz_benchmark.sh) crashed on, replayed through the same
// decoding as the harnesses: none may throw what its decoder does not document (nor, in the
// sanitized build, touch memory it does not own). Plus the faults they found, written out.
#include <gtest/gtest.h>
#include <ros/message_traits.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/image_encodings.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "ply_slam/MappingJobMsg.h"
#include "ply_slam/ros/conversions.h"
#include "ply_slam/ros/rgbd_message_decoder.h"
#include "target_inputs.h"

namespace fs = std::filesystem;
namespace enc = sensor_msgs::image_encodings;

namespace {

std::vector<uint8_t> readBytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// rgb8 whose width times 3 bytes wraps round to 2 in 32 bits: a 2-byte row "holds" it.
sensor_msgs::Image wrappingImage() {
  sensor_msgs::Image image;
  image.encoding = enc::RGB8;
  image.width = 0x55555556u;
  image.height = 1;
  image.step = 2;
  image.data.assign(2, 0);
  return image;
}

template <typename Msg>
std::string layoutOf() {
  return ros::message_traits::MD5Sum<Msg>::value();
}

// What each message target's inputs are serialised as today: the definitions' MD5 sums, as ROS
// compares a publisher's and a subscriber's.
std::map<std::string, std::string> todaysLayouts() {
  using sensor_msgs::CameraInfo;
  using sensor_msgs::Image;
  return {{"fuzz_rgbd_decoder",
           layoutOf<Image>() + " " + layoutOf<Image>() + " " + layoutOf<CameraInfo>()},
          {"fuzz_keyframe_msg", layoutOf<ply_slam::KeyFrameMsg>()},
          {"fuzz_map_update_msg", layoutOf<ply_slam::MapUpdateMsg>()},
          {"fuzz_map_snapshot_msg", layoutOf<ply_slam::MapSnapshotMsg>()},
          {"fuzz_mapping_job_msg", layoutOf<ply_slam::MappingJobMsg>()}};
}

const fs::path& savedInputs() {
  static const fs::path root = fs::path(PLY_SLAM_SOURCE_DIR) / "test" / "fuzz_regressions";
  return root;
}

}  // namespace

// Bytes saved in another layout of their message misparse: the replay then tests nothing, or
// (stop 44) reads a declared array of 20 GB. layouts.txt says what each folder was written in.
TEST(FuzzRegressions, SavedMessagesAreInTodaysLayouts) {
  std::ifstream in(savedInputs() / "layouts.txt");
  ASSERT_TRUE(in) << "no " << savedInputs() / "layouts.txt";
  std::map<std::string, std::string> saved;
  for (std::string line; std::getline(in, line);) {
    std::istringstream fields(line);
    std::string target;
    if (!(fields >> target) || target[0] == '#') continue;
    std::getline(fields >> std::ws, saved[target]);
  }
  for (const auto& [target, layout] : todaysLayouts()) {
    if (!fs::is_directory(savedInputs() / target)) continue;
    EXPECT_EQ(saved[target], layout)
        << target << ": its message changed since its inputs were saved; write them again in "
        << "today's layout (scripts/reencode_fuzz_inputs.py) and put the new sum in layouts.txt";
  }
}

namespace {

// Every input in root/<target>/ through its target; returns how many.
size_t replayFolders(const fs::path& root) {
  size_t replayed = 0;
  for (const auto& folder : fs::directory_iterator(root)) {
    if (!folder.is_directory()) continue;  // layouts.txt
    const auto target = ply_slam_fuzz::targets().find(folder.path().filename().string());
    EXPECT_NE(target, ply_slam_fuzz::targets().end()) << "no fuzz target " << folder.path();
    if (target == ply_slam_fuzz::targets().end()) continue;
    for (const auto& input : fs::directory_iterator(folder.path())) {
      const std::vector<uint8_t> bytes = readBytes(input.path());
      EXPECT_NO_THROW(target->second(bytes.data(), bytes.size())) << input.path();
      ++replayed;
    }
  }
  return replayed;
}

}  // namespace

TEST(FuzzRegressions, SavedInputsReplayCleanly) { EXPECT_GT(replayFolders(savedInputs()), 0u); }

// The committed corpora (fuzz/corpus/<target>, minimised): the Release suite covers what the
// fuzzer reached without clang.
TEST(FuzzRegressions, SavedCorporaReplayCleanly) {
  EXPECT_GT(replayFolders(fs::path(PLY_SLAM_SOURCE_DIR) / "fuzz" / "corpus"), 0u);
}

TEST(FuzzRegressions, KeyFrameImageWithShortRowsIsInvalidArgument) {
  ply_slam::KeyFrameMsg msg;
  msg.T_wc.orientation.w = 1.0;
  msg.rgb.encoding = enc::BGR8;
  msg.rgb.width = 195;  // the fuzzer's: 48-byte rows for 195 pixels
  msg.rgb.height = 1;
  msg.rgb.step = 48;
  msg.rgb.data.assign(48, 0);
  EXPECT_THROW(ply_slam::fromMsg(msg), std::invalid_argument);
  msg.rgb.step = 585;  // rows long enough, but no data
  msg.rgb.data.clear();
  EXPECT_THROW(ply_slam::fromMsg(msg), std::invalid_argument);
}

TEST(FuzzRegressions, WidthThatWrapsRoundIsRejected) {
  ply_slam::KeyFrameMsg msg;
  msg.T_wc.orientation.w = 1.0;
  msg.rgb = wrappingImage();
  msg.rgb.encoding = enc::BGR8;
  EXPECT_THROW(ply_slam::fromMsg(msg), std::invalid_argument);

  sensor_msgs::Image depth = wrappingImage();
  depth.encoding = enc::TYPE_16UC1;  // 2 bytes a pixel: wraps round to 0x0000000c
  depth.step = 12;
  depth.data.assign(12, 0);
  ply_slam::RgbdMessageDecoder decoder;
  try {
    decoder.decode(wrappingImage(), depth, nullptr);
    FAIL() << "decoded an image of 0x55555556 pixels from 2 bytes";
  } catch (const ply_slam::BadRgbdMessage& e) {
    EXPECT_EQ(e.kind(), "size") << e.what();
  }
}

// Found by fuzz/fuzz_rgbd_decoder: cv_bridge turns big-endian 32FC1 into an 8UC4 image (the
// decoder then failed in patchNaNs; a keyframe's depth was kept as bytes).
TEST(FuzzRegressions, BigEndianDepthIsRejected) {
  sensor_msgs::Image rgb, depth;
  rgb.encoding = enc::RGB8;
  rgb.width = depth.width = 4;
  rgb.height = depth.height = 2;
  rgb.step = 12;
  rgb.data.assign(24, 0);
  rgb.header.stamp.sec = 1;
  depth.encoding = enc::TYPE_32FC1;
  depth.step = 16;
  depth.data.assign(32, 0);
  depth.is_bigendian = 1;
  try {
    ply_slam::RgbdMessageDecoder().decode(rgb, depth, nullptr);
    FAIL() << "decoded big-endian depth";
  } catch (const ply_slam::BadRgbdMessage& e) {
    EXPECT_EQ(e.kind(), "encoding") << e.what();
  }

  // A keyframe that is valid but for its depth's byte order (a valid camera: the camera is
  // checked before the images).
  ply_slam::KeyFramePacket packet;
  packet.camera.fx = packet.camera.fy = 500.0;
  packet.camera.cx = 2.0, packet.camera.cy = 1.0;
  packet.camera.width = 4, packet.camera.height = 2;
  packet.camera.depth_factor = 5000, packet.camera.min_depth = 0.3, packet.camera.max_depth = 6;
  packet.camera.depth_noise = {2.5e-5, 1e-6, 1e-5, 0.0};
  ply_slam::KeyFrameMsg msg = ply_slam::toMsg(packet, "map");
  ASSERT_NO_THROW(ply_slam::fromMsg(msg));
  msg.depth = depth;
  EXPECT_THROW(ply_slam::fromMsg(msg), std::invalid_argument);
  msg.depth.is_bigendian = 0;
  EXPECT_EQ(ply_slam::fromMsg(msg).depth.type(), CV_32FC1);
}
