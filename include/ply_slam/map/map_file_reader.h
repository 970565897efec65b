#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "ply_slam/map/map_file_contents.h"

namespace ply_slam {

// Reads a map file (map_file_format.h) for a system set up as `expected`.
class MapFileReader {
 public:
  // `scales`: the ORB pyramid's scale per level (the extractor's; outlives the keyframes).
  // Throws std::runtime_error naming the file and the fault: missing or unreadable, not a map
  // file, another format version, truncated, checksum mismatch (corrupted), made with another
  // camera, ORB pyramid or vocabulary (both named), or inconsistent content.
  static MapFileContents read(const std::string& path, const MapFileSetup& expected,
                              const std::vector<double>* scales);
  // So, a map file's bytes (MapFileWriter::encode) that came another way than from a file
  // (`name` says where in errors).
  static MapFileContents decode(const std::vector<uint8_t>& bytes, const std::string& name,
                                const MapFileSetup& expected, const std::vector<double>* scales);
};

}  // namespace ply_slam
