#pragma once

#include "ply_slam/mapping/key_frame_culler_options.h"
#include "ply_slam/mapping/map_point_culler_options.h"

namespace ply_slam {

// The `culling:` section: what the mapping side retires after each keyframe.
struct CullingOptions {
  KeyFrameCullerOptions keyframes;
  MapPointCullerOptions points;
};

}  // namespace ply_slam
