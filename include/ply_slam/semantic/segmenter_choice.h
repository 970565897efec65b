#pragma once

#include <memory>
#include <string>

#include "ply_slam/semantic/segmenter.h"
#include "ply_slam/semantic/yolo_options.h"

namespace ply_slam {

// The segmenter a tool's command line asks for: --segmenter none|masks|yolo, --model ONNX and
// --input WxH (which replace the config's segmentation.model and input size).
struct SegmenterChoice {
  std::string kind = "none";
  std::string model;
  int input_width = 0, input_height = 0;

  // Takes --segmenter, --model and --input, and returns false for any other option. Throws
  // std::invalid_argument for a value it cannot use.
  bool take(const std::string& option, const std::string& value);
  // --model or --input without --segmenter yolo would be ignored: std::invalid_argument.
  void check() const;
  // nullptr for none; masks come from `sequence_folder`.
  std::unique_ptr<Segmenter> make(const YoloOptions& config,
                                  const std::string& sequence_folder) const;
};

}  // namespace ply_slam
