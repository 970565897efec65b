#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "ply_slam/map/map.h"
#include "ply_slam/map/map_file_contents.h"

namespace ply_slam {

// Writes a map file (the layout is in map_file_format.h): a map that loads again
// (MapFileReader). Bad landmarks and links to them are left out.
class MapFileWriter {
 public:
  // The file's bytes.
  static std::vector<uint8_t> encode(const MapFileSetup& setup, const Map& map,
                                     const std::map<long, KeyFramePlace>& places);
  // Through AtomicFile: whole or not there. Throws std::runtime_error naming the file.
  static void write(const std::string& path, const MapFileSetup& setup, const Map& map,
                    const std::map<long, KeyFramePlace>& places);
};

}  // namespace ply_slam
