#pragma once

#include <string>
#include <vector>

#include "ply_slam/common/enum_words.h"
#include "ply_slam/dynamic/dynamic_filter_options.h"

namespace ply_slam {

// off: use every feature; geometric: the Delaunay check, per feature and per depth surface;
// semantic: drop instances of active classes whole, no geometry; full: the paper's fusion of
// both (without a segmenter: geometric, modeWithoutSegmenter).
enum class DynamicMode { kOff, kGeometric, kSemantic, kFull };
inline constexpr EnumWord<DynamicMode> kDynamicModeWords[] = {
    {DynamicMode::kOff, "off"},
    {DynamicMode::kGeometric, "geometric"},
    {DynamicMode::kSemantic, "semantic"},
    {DynamicMode::kFull, "full"}};
// The mode a word names ("off", "geometric", "semantic", "full"); std::invalid_argument else.
DynamicMode parseDynamicMode(const std::string& mode);
inline const char* toString(DynamicMode mode) { return wordOf(kDynamicModeWords, mode); }
// Full mode without a segmenter has no labels to fuse: it judges the depth image's surfaces as
// geometric mode does. Returns the mode to run with; the others are unchanged.
inline DynamicMode modeWithoutSegmenter(DynamicMode mode) {
  return mode == DynamicMode::kFull ? DynamicMode::kGeometric : mode;
}

// Dynamic-feature rejection (the config's `dynamic:` section).
struct DynamicOptions {
  DynamicMode mode = DynamicMode::kFull;
  DynamicFilterOptions filter;
  int mask_dilation_px = 5;  // dynamic masks miss the blurred rim of a moving object
  // Frames back to the frame the Delaunay check compares with: a person walking at 1 m/s moves
  // 3 cm between two 30 Hz frames, within the depth noise at 3 m; over 0.1 s it moves 10 cm.
  int baseline_frames = 3;
  // A dynamic instance the segmenter misses is carried on (by its flow) for this many frames.
  int carry_frames = 5;
  double match_radius_px = 30.0;  // previous -> current feature search around the prediction
  int max_descriptor_distance = 50;
  std::vector<std::string> active_classes = {
      "person", "bicycle", "car",   "motorcycle", "bus", "train",    "truck", "boat",  "bird",
      "cat",    "dog",     "horse", "sheep",      "cow", "elephant", "bear",  "zebra", "giraffe"};
  std::vector<std::string> passive_classes = {"chair",      "backpack",    "handbag",   "suitcase",
                                              "umbrella",   "bottle",      "cup",       "book",
                                              "cell phone", "sports ball", "teddy bear"};
};

}  // namespace ply_slam
