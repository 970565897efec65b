#pragma once

#include "ply_slam/common/enum_words.h"

namespace ply_slam {

// What colours an octree voxel: its majority class (the palette) or the mean RGB of its points.
enum class OctreeColourMode { kClass, kRgb };
inline constexpr EnumWord<OctreeColourMode> kOctreeColourModeWords[] = {
    {OctreeColourMode::kClass, "class"}, {OctreeColourMode::kRgb, "rgb"}};

}  // namespace ply_slam
