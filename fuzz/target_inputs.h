#pragma once

// What each fuzz target does with one input, shared by the libFuzzer harnesses (fuzz_*.cpp)
// and the regression test that replays the inputs they found (test/ros/test_fuzz_regressions).
// Each throws only what the function under test does not document; everything else it
// catches, as its caller in the nodes and tools does.
#include <cstddef>
#include <cstdint>
#include <map>
#include <string>

namespace ply_slam_fuzz {

using Target = void (*)(const uint8_t* data, size_t size);

void configText(const uint8_t* data, size_t size);      // loadConfigFromString
void tumLists(const uint8_t* data, size_t size);        // TumSequence, readTumTrajectory
void rgbdMessages(const uint8_t* data, size_t size);    // RgbdMessageDecoder
void keyFrameMsg(const uint8_t* data, size_t size);     // fromMsg(KeyFrameMsg)
void mapUpdateMsg(const uint8_t* data, size_t size);    // fromMsg(MapUpdateMsg)
void mapSnapshotMsg(const uint8_t* data, size_t size);  // fromMsg(MapSnapshotMsg)
void mappingJobMsg(const uint8_t* data, size_t size);   // fromMsg(MappingJobMsg)

// By target name (fuzz_config, ...): the folder names under test/fuzz_regressions.
const std::map<std::string, Target>& targets();

}  // namespace ply_slam_fuzz
