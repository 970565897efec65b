#pragma once

#include <cstddef>
#include <cstdint>

namespace ply_slam {

// 64-bit FNV-1a hash (Fowler, Noll, Vo): a cheap check that a file was not cut or altered.
inline uint64_t fnv1a64(const uint8_t* data, size_t size) {
  uint64_t hash = 0xcbf29ce484222325ull;  // offset basis
  for (size_t i = 0; i < size; ++i) {
    hash ^= data[i];
    hash *= 0x100000001b3ull;  // FNV prime
  }
  return hash;
}

}  // namespace ply_slam
