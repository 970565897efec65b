#pragma once

#include <map>
#include <string>

#include "ply_slam/semantic/segmenter.h"

namespace ply_slam {

// Precomputed instance masks, as in the synthetic scenes and the shared walkers sequence:
// <folder>/masks/<rgb stamp, 6 decimals>.png holds instance ids (8-bit, 0 = none) and
// <folder>/instances.txt lists "id class_name ..." per line ('#' comments).
class MaskFolderSegmenter : public Segmenter {
 public:
  explicit MaskFolderSegmenter(const std::string& folder);

  std::vector<Instance> segment(const RgbdImages& images) override;
  std::string name() const override { return "masks"; }

 private:
  std::string folder_;
  std::map<int, std::string> classes_;  // instance id -> class name
};

// Reads an instances.txt: "id class_name [more fields]" per line, '#' comments; a class name of
// several words is written with '_' for its spaces ("dining_table"; COCO names have no '_').
// Throws naming the file and line on a malformed line.
std::map<int, std::string> readInstanceClasses(const std::string& path);

}  // namespace ply_slam
