// libFuzzer entry point; what it does with an input: ply_slam_fuzz::mappingJobMsg
// (target_inputs.h).
#include "target_inputs.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  ply_slam_fuzz::mappingJobMsg(data, size);
  return 0;
}
