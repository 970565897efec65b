#include "target_inputs.h"

#include <ros/serialization.h>
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <new>
#include <stdexcept>
#include <vector>

#include "ply_slam/io/tum_sequence.h"
#include "ply_slam/io/tum_trajectory_file.h"
#include "ply_slam/ros/conversions.h"
#include "ply_slam/ros/rgbd_message_decoder.h"
#include "ply_slam/ros/split_messages.h"
#include "ply_slam/system/system_config.h"

namespace ply_slam_fuzz {
namespace {

// Reads `messages` one after another from the same bytes, as a subscriber would receive them.
// False when the bytes run out or a declared length is too large to allocate (the fuzzers cap
// allocations, bounded_new.cpp): no subscriber gets such a message, so no decoder sees it.
template <typename... Messages>
bool deserialize(const uint8_t* data, size_t size, Messages&... messages) {
  try {
    ros::serialization::IStream stream(const_cast<uint8_t*>(data), static_cast<uint32_t>(size));
    (ros::serialization::deserialize(stream, messages), ...);
    return true;
  } catch (const ros::serialization::StreamOverrunException&) {
    return false;
  } catch (const std::bad_alloc&) {
    return false;
  } catch (const std::length_error&) {
    return false;
  }
}

// The TUM readers take paths: one folder per process, its files rewritten for every input.
const std::string& tumFolder() {
  static const std::string path = [] {
    std::string pattern = "/tmp/ply_slam_fuzz_tum_XXXXXX";
    if (!mkdtemp(pattern.data())) throw std::runtime_error("cannot make a temporary folder");
    return pattern;
  }();
  return path;
}

void putFile(const std::string& name, const std::string& text) {
  const std::string path = tumFolder() + "/" + name;
  if (text.empty() && name != "rgb.txt") {  // no such file (rgb.txt is required: kept)
    unlink(path.c_str());
    return;
  }
  std::ofstream(path, std::ios::binary) << text;
}

}  // namespace

void configText(const uint8_t* data, size_t size) {
  try {
    ply_slam::loadConfigFromString(std::string(reinterpret_cast<const char*>(data), size), "fuzz");
  } catch (const ply_slam::ConfigError&) {  // documented: names the key that is wrong
  }
}

// The input holds rgb.txt, depth.txt, associations.txt and groundtruth.txt separated by NUL
// bytes; an absent or empty part is no file.
void tumLists(const uint8_t* data, size_t size) {
  std::vector<std::string> parts(1);
  for (size_t i = 0; i < size; ++i) {
    if (data[i] == 0 && parts.size() < 4)
      parts.emplace_back();
    else
      parts.back().push_back(static_cast<char>(data[i]));
  }
  parts.resize(4);
  const char* names[] = {"rgb.txt", "depth.txt", "associations.txt", "groundtruth.txt"};
  for (int i = 0; i < 4; ++i) putFile(names[i], parts[i]);
  try {
    ply_slam::TumSequence sequence(tumFolder());
  } catch (const std::runtime_error&) {  // documented: names the file (and line)
  }
  if (parts[3].empty()) return;
  try {
    ply_slam::readTumTrajectory(tumFolder() + "/groundtruth.txt");
  } catch (const std::runtime_error&) {
  }
}

// A colour image, a depth image and a camera_info; decoded with and without the camera_info
// by one decoder, so that the second decode sees a previous stamp.
void rgbdMessages(const uint8_t* data, size_t size) {
  sensor_msgs::Image rgb, depth;
  sensor_msgs::CameraInfo info;
  if (!deserialize(data, size, rgb, depth, info)) return;
  ply_slam::RgbdMessageDecoder decoder;
  for (const sensor_msgs::CameraInfo* i : {&info, static_cast<sensor_msgs::CameraInfo*>(nullptr)}) {
    try {
      decoder.decode(rgb, depth, i);
    } catch (const ply_slam::BadRgbdMessage&) {  // documented: the node counts and skips it
    }
  }
}

template <typename Msg>
void decodeMessage(const uint8_t* data, size_t size) {
  Msg msg;
  if (!deserialize(data, size, msg)) return;
  try {
    ply_slam::fromMsg(msg);
  } catch (const std::invalid_argument&) {  // documented: an inconsistent message
  }
}

void keyFrameMsg(const uint8_t* data, size_t size) {
  decodeMessage<ply_slam::KeyFrameMsg>(data, size);
}
void mapUpdateMsg(const uint8_t* data, size_t size) {
  decodeMessage<ply_slam::MapUpdateMsg>(data, size);
}
void mapSnapshotMsg(const uint8_t* data, size_t size) {
  decodeMessage<ply_slam::MapSnapshotMsg>(data, size);
}
void mappingJobMsg(const uint8_t* data, size_t size) {
  ply_slam::MappingJobMsg msg;
  if (!deserialize(data, size, msg)) return;
  static const std::vector<double> scales{1.0, 1.2, 1.44, 1.728};  // a pyramid of 4 levels
  try {
    ply_slam::fromMsg(msg, {&scales, cv::Size(16, 12)});  // the seeds' size (fuzz_seeds.py)
  } catch (const std::invalid_argument&) {                // documented: an inconsistent message
  }
}

const std::map<std::string, Target>& targets() {
  static const std::map<std::string, Target> all{{"fuzz_config", configText},
                                                 {"fuzz_tum_lists", tumLists},
                                                 {"fuzz_rgbd_decoder", rgbdMessages},
                                                 {"fuzz_keyframe_msg", keyFrameMsg},
                                                 {"fuzz_map_update_msg", mapUpdateMsg},
                                                 {"fuzz_map_snapshot_msg", mapSnapshotMsg},
                                                 {"fuzz_mapping_job_msg", mappingJobMsg}};
  return all;
}

}  // namespace ply_slam_fuzz
