#pragma once

#include <string>

#include "ply_slam/loop/vocabulary_data.h"

namespace ply_slam {

// The vocabulary file, little-endian:
//   "PLYVOCAB" | u32 version | u32 kind (0 orb, 1 lbd) | u32 k | u32 L | u32 descriptor bits |
//   u32 nodes | u32 words | u32 parent per node | centres (nodes x bits/8 bytes) |
//   f64 idf per word | u64 FNV-1a of every byte before it.
class VocabularyFile {
 public:
  static constexpr uint32_t kVersion = 1;

  // Writes a temporary file beside `path` and renames it over `path`, so a failed or
  // interrupted save leaves no half file. Throws std::runtime_error naming the file.
  static void write(const std::string& path, const VocabularyData& data);
  // The checksum the file of `data` ends with: what names a vocabulary's exact content (a map
  // file records it and refuses another vocabulary).
  static uint64_t checksum(const VocabularyData& data);
  // Throws std::runtime_error naming the file and the fault: missing or unreadable, truncated,
  // not a vocabulary (magic), another version, checksum mismatch, another descriptor kind, or
  // an inconsistent tree.
  static VocabularyData read(const std::string& path, DescriptorKind expected_kind);
};

}  // namespace ply_slam
