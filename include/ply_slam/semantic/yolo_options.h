#pragma once

#include <string>

namespace ply_slam {

// YOLOv8-seg instance segmentation (the config's `segmentation:` section).
struct YoloOptions {
  std::string model_path;        // ONNX export with a fixed input size (README); "" = none
  std::string class_names_path;  // one class name per line, in the model's order
  int input_width = 640;         // the export's input size
  int input_height = 640;
  float score_threshold = 0.25f;  // keep detections whose best class score is above
  float nms_threshold = 0.5f;     // IoU above which the weaker box of one class is dropped
  float mask_threshold = 0.5f;    // sigmoid mask probability that counts as inside
};

}  // namespace ply_slam
