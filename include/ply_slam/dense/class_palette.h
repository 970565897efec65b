#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace ply_slam {

// 8-bit RGB colour of a class.
struct ClassColour {
  std::uint8_t r = 0, g = 0, b = 0;
  bool operator==(const ClassColour& o) const { return r == o.r && g == o.g && b == o.b; }
};

// The labels of the dense maps: 0 = "unknown" (no instance), 1..80 = the COCO classes in the
// order of coco.names (person = 1). A fixed colour per label, so maps of different runs can be
// compared; a palette file may override colours by class name.
class ClassPalette {
 public:
  static constexpr std::uint32_t kUnknown = 0;

  ClassPalette();  // built-in colours

  // Reads "r g b class name" lines ('#' comments) over the built-in colours. Throws
  // std::runtime_error naming the file and line on an unknown class or a bad colour.
  static ClassPalette fromFile(const std::string& path);
  // dense.palette: the file's colours, or the built-in ones when the path is empty.
  static ClassPalette configured(const std::string& path) {
    return path.empty() ? ClassPalette() : fromFile(path);
  }

  size_t size() const { return names_.size(); }
  const std::string& name(std::uint32_t label) const;  // "unknown" for an unknown label
  ClassColour colour(std::uint32_t label) const;       // unknown's colour for an unknown label
  std::uint32_t label(const std::string& class_name) const;  // kUnknown when not a COCO class

  // "label r g b class name" per line, the labels in `labels` only (all when empty).
  void writeLegend(const std::string& path, const std::vector<std::uint32_t>& labels = {}) const;

 private:
  std::vector<std::string> names_;
  std::vector<ClassColour> colours_;
};

}  // namespace ply_slam
