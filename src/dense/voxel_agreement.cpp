#include "ply_slam/dense/voxel_agreement.h"

#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <unordered_set>

namespace ply_slam {
namespace {

// Voxel grid index packed into 64 bits (21 bits per axis, offset to stay positive).
std::int64_t cell(long x, long y, long z) {
  constexpr long kOffset = 1 << 20;
  return ((x + kOffset) << 42) | ((y + kOffset) << 21) | (z + kOffset);
}

std::unordered_set<std::int64_t> cells(const std::vector<SemanticOctree::Voxel>& voxels,
                                       double resolution) {
  std::unordered_set<std::int64_t> out;
  for (const auto& v : voxels) {
    if (v.size > 1.5 * resolution)
      throw std::invalid_argument("compareOccupiedVoxels: voxel larger than the resolution");
    out.insert(cell(std::lround(std::floor(v.centre.x() / resolution)),
                    std::lround(std::floor(v.centre.y() / resolution)),
                    std::lround(std::floor(v.centre.z() / resolution))));
  }
  return out;
}

size_t withNeighbourIn(const std::unordered_set<std::int64_t>& from,
                       const std::unordered_set<std::int64_t>& in) {
  constexpr long kOffset = 1 << 20, kMask = (1 << 21) - 1;
  size_t n = 0;
  for (const std::int64_t c : from) {
    const long x = (c >> 42) - kOffset, y = ((c >> 21) & kMask) - kOffset,
               z = (c & kMask) - kOffset;
    bool found = false;
    for (long dx = -1; dx <= 1 && !found; ++dx)
      for (long dy = -1; dy <= 1 && !found; ++dy)
        for (long dz = -1; dz <= 1 && !found; ++dz) found = in.count(cell(x + dx, y + dy, z + dz));
    n += found;
  }
  return n;
}

}  // namespace

VoxelAgreement compareOccupiedVoxels(const std::vector<SemanticOctree::Voxel>& a,
                                     const std::vector<SemanticOctree::Voxel>& b,
                                     double resolution) {
  if (!(resolution > 0.0)) throw std::invalid_argument("compareOccupiedVoxels: resolution <= 0");
  const auto A = cells(a, resolution), B = cells(b, resolution);
  VoxelAgreement r;
  r.a = A.size();
  r.b = B.size();
  for (const std::int64_t c : A) r.both += B.count(c);
  const size_t either = r.a + r.b - r.both;
  r.iou = either ? double(r.both) / either : 1.0;
  r.a_in_b = r.a ? double(r.both) / r.a : 1.0;
  r.tolerant =
      r.a + r.b ? double(withNeighbourIn(A, B) + withNeighbourIn(B, A)) / (r.a + r.b) : 1.0;
  return r;
}

}  // namespace ply_slam
