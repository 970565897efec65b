#pragma once

#include <vector>

#include "ply_slam/dense/semantic_octree.h"

namespace ply_slam {

// How well two sets of occupied voxels (same resolution and grid) agree.
struct VoxelAgreement {
  size_t a = 0, b = 0;  // occupied voxels of each
  size_t both = 0;      // |A ∩ B|: the same voxel occupied in both
  double iou = 0.0;     // strict: |A ∩ B| / |A ∪ B|
  double a_in_b = 0.0;  // strict: |A ∩ B| / |A|
  // Tolerant (labelled as such wherever reported): a voxel agrees when the other set has an
  // occupied voxel among its 27 neighbours (itself included), i.e. within one voxel.
  double tolerant = 0.0;  // (agreeing of A + agreeing of B) / (|A| + |B|)
};

VoxelAgreement compareOccupiedVoxels(const std::vector<SemanticOctree::Voxel>& a,
                                     const std::vector<SemanticOctree::Voxel>& b,
                                     double resolution);

}  // namespace ply_slam
