#pragma once

#include <string>

#include "ply_slam/dense/octree_colour_mode.h"

namespace ply_slam {

// Dense and semantic octree maps (the config's `dense:` section): keyframe point clouds without
// the pixels of moving things, and an OctoMap ColorOcTree coloured by class.
struct DenseOptions {
  bool enabled = true;              // false: no dense map, no octree
  int stride = 2;                   // px between sampled pixels, in both directions
  double min_depth = 0.3;           // m; pixels nearer or farther are left out
  double max_depth = 4.0;           // m; depth noise grows as Z^2
  double voxel_size = 0.02;         // m; voxel filter of keyframe clouds and the global cloud
  int dilation_px = 0;              // extra dilation of the keyframe's dynamic mask
  double octree_resolution = 0.05;  // m; leaf size of the semantic octree
  // OctoMap probability from which a voxel counts as occupied. A hit adds 0.85 log-odds, a
  // ray through takes 0.41: 0.5 = one hit; 0.88 = at least three hits more than... (see yaml)
  double octree_occupancy = 0.88;
  // m; a ray frees the voxels it passes only up to this short of its hit, whose place is
  // uncertain by the depth noise and the keyframe's pose (see yaml)
  double ray_margin = 0.1;
  bool octree_filter = true;  // the dense cloud keeps only points in occupied octree voxels
  OctreeColourMode colour_mode = OctreeColourMode::kClass;  // config words "class", "rgb"
  std::string palette;  // file of "class r g b" lines overriding the built-in palette; "" = none
};

}  // namespace ply_slam
