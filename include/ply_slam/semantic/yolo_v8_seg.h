#pragma once

#include <opencv2/dnn.hpp>
#include <string>
#include <vector>

#include "ply_slam/semantic/segmenter.h"

namespace ply_slam {

struct YoloParams {
  std::string model_path;        // ONNX export with a fixed input size (see README)
  std::string class_names_path;  // one class name per line, in the model's order
  int input_width = 640;         // the export's input size
  int input_height = 640;
  float score_threshold = 0.35f;  // keep detections whose best class score is above
  float nms_threshold = 0.5f;     // IoU above which the weaker box of one class is dropped
  float mask_threshold = 0.5f;    // sigmoid mask probability that counts as inside
};

// YOLOv8-seg instance segmentation through OpenCV DNN on the CPU: letterbox, one forward
// pass, decoding of boxes, class scores and mask coefficients, class-aware NMS, and masks
// (sigmoid of coefficients x prototypes, cropped to the box) mapped back to full resolution.
class YoloV8Seg : public Segmenter {
 public:
  // Throws std::runtime_error naming the file and what OpenCV said when the model or the
  // class list cannot be loaded.
  explicit YoloV8Seg(const YoloParams& params);

  std::vector<Instance> segment(const RgbdImages& images) override;
  std::string name() const override { return "yolo"; }
  const std::vector<std::string>& classNames() const { return class_names_; }

 private:
  YoloParams params_;
  cv::dnn::Net net_;
  std::vector<std::string> class_names_;
};

}  // namespace ply_slam
