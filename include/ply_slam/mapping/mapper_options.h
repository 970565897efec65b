#pragma once

#include "ply_slam/features/line_options.h"
#include "ply_slam/features/orb_options.h"
#include "ply_slam/loop/loop_options.h"
#include "ply_slam/mapping/culling_options.h"
#include "ply_slam/mapping/local_mapping_options.h"
#include "ply_slam/mapping/loop_correction_options.h"

namespace ply_slam {

// What the mapping side (Mapper) is set up with: its own sections and the few settings of the
// front end it has to agree with.
struct MapperOptions {
  LocalMappingOptions local;
  CullingOptions culling;
  LoopOptions loop;                       // place recognition (loop.enabled: at all)
  LoopCorrectionOptions loop_correction;  // closing an accepted loop
  OrbOptions orb;                         // the keyframes' pyramid: landmarks' predicted levels
  LineOptions lines;  // new line landmarks (lines.enabled), place recognition's line words
  double max_point_depth = 6.0;  // tracking.max_point_depth: deeper points make no landmark
  int mask_dilation_px = 5;  // dynamic.mask_dilation_px: instances left out of place recognition
};

}  // namespace ply_slam
