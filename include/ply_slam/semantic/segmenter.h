#pragma once

#include <string>
#include <vector>

#include "ply_slam/io/rgbd_images.h"
#include "ply_slam/semantic/instance.h"

namespace ply_slam {

// Instance segmentation of an RGB-D frame.
class Segmenter {
 public:
  virtual ~Segmenter() = default;
  // Throws std::runtime_error naming what is wrong when the frame cannot be segmented.
  virtual std::vector<Instance> segment(const RgbdImages& images) = 0;
  virtual std::string name() const = 0;
  // What runs, for a log line at the start (a model's file, size, where it runs).
  virtual std::string description() const { return name(); }
};

}  // namespace ply_slam
