#include "ply_slam/semantic/segmenter_choice.h"

#include <stdexcept>
#include <tuple>

#include "ply_slam/common/number_text.h"
#include "ply_slam/semantic/mask_folder_segmenter.h"
#include "ply_slam/semantic/yolo_v8_seg.h"

namespace ply_slam {

bool SegmenterChoice::take(const std::string& option, const std::string& value) {
  if (option == "--segmenter") {
    if (value != "none" && value != "masks" && value != "yolo")
      throw std::invalid_argument("unknown segmenter '" + value + "' (none, masks or yolo)");
    kind = value;
  } else if (option == "--model") {
    model = value;
  } else if (option == "--input") {
    const auto size = parseImageSize(value);
    if (!size) throw std::invalid_argument("--input needs WxH, e.g. 320x320, got '" + value + "'");
    std::tie(input_width, input_height) = *size;
  } else {
    return false;
  }
  return true;
}

void SegmenterChoice::check() const {
  if ((!model.empty() || input_width > 0) && kind != "yolo")
    throw std::invalid_argument("--model and --input need --segmenter yolo");
}

std::unique_ptr<Segmenter> SegmenterChoice::make(const YoloOptions& config,
                                                 const std::string& sequence_folder) const {
  if (kind == "masks") return std::make_unique<MaskFolderSegmenter>(sequence_folder);
  if (kind != "yolo") return nullptr;
  YoloOptions yolo = config;
  if (!model.empty()) yolo.model_path = model;
  if (input_width > 0) {
    yolo.input_width = input_width;
    yolo.input_height = input_height;
  }
  return std::make_unique<YoloV8Seg>(yolo);
}

}  // namespace ply_slam
