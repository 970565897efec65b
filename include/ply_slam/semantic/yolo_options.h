#pragma once

#include <string>

namespace ply_slam {

// Where OpenCV DNN runs the network (cv::dnn::Backend / Target); what a build has is checked
// when the model is loaded.
enum class DnnBackend { kOpenCv, kCuda, kInferenceEngine };
enum class DnnTarget { kCpu, kOpenCl, kOpenClFp16, kCuda, kCudaFp16 };

// YOLOv8-seg instance segmentation (the config's `segmentation:` section).
struct YoloOptions {
  std::string model_path;        // ONNX export with a fixed input size (docs/TOOLS.md); "" = none
  std::string class_names_path;  // one class name per line, in the model's order
  // The export's input size; 0 = read from the model (a fixed-size export says its own).
  int input_width = 0;
  int input_height = 0;
  float score_threshold = 0.25f;  // keep detections whose best class score is above
  float nms_threshold = 0.5f;     // IoU above which the weaker box of one class is dropped
  float mask_threshold = 0.5f;    // sigmoid mask probability that counts as inside
  DnnBackend backend = DnnBackend::kOpenCv;
  DnnTarget target = DnnTarget::kCpu;
  // OpenCV threads while the network runs live beside tracking (LiveSegmenter; process-wide,
  // cv::setNumThreads); 0 = OpenCV's default, every core. Offline, segmentation runs alone.
  int live_threads = 1;
};

}  // namespace ply_slam
