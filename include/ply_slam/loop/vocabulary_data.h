#pragma once

#include <cstdint>
#include <vector>

#include "ply_slam/loop/descriptor_kind.h"

namespace ply_slam {

// A vocabulary tree as plain arrays: what training produces and the file holds. Node 0 is the
// root; the children of a node have consecutive ids (made together by one k-means); a node
// without children is a leaf, and leaves in id order are the words 0, 1, 2, ...
struct VocabularyData {
  static constexpr uint32_t kNoParent = 0xFFFFFFFFu;

  DescriptorKind kind = DescriptorKind::kOrb;
  int branching = 10;             // k
  int levels = 5;                 // L: depth of the deepest leaf (the root is depth 0)
  int descriptor_bytes = 32;      // 256 bits for both ORB and LBD
  std::vector<uint32_t> parents;  // per node; kNoParent for the root
  std::vector<uint8_t> centres;   // per node, descriptor_bytes each (the root's is unused)
  std::vector<double> idf;        // per word: log(N images / images containing it)

  size_t numNodes() const { return parents.size(); }
};

}  // namespace ply_slam
