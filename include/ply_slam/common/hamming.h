#pragma once

#include <cstdint>
#include <cstring>

namespace ply_slam {

// Bits that differ between two binary descriptors of `bytes` bytes, 8 bytes at a time.
inline int hammingDistance(const uint8_t* a, const uint8_t* b, int bytes) {
  int distance = 0;
  int i = 0;
  for (; i + 8 <= bytes; i += 8) {
    uint64_t x, y;
    std::memcpy(&x, a + i, 8);  // memcpy: rows need not be 8-byte aligned
    std::memcpy(&y, b + i, 8);
    distance += __builtin_popcountll(x ^ y);
  }
  for (; i < bytes; ++i) distance += __builtin_popcount(static_cast<unsigned>(a[i] ^ b[i]));
  return distance;
}

}  // namespace ply_slam
