#pragma once

#include <opencv2/dnn.hpp>
#include <string>
#include <vector>

#include "ply_slam/semantic/segmenter.h"
#include "ply_slam/semantic/yolo_options.h"

namespace ply_slam {

// YOLOv8-seg instance segmentation through OpenCV DNN on the CPU: letterbox, one forward
// pass, decoding of boxes, class scores and mask coefficients, class-aware NMS, and masks
// (sigmoid of coefficients x prototypes, cropped to the box) mapped back to full resolution.
class YoloV8Seg : public Segmenter {
 public:
  // Throws std::runtime_error naming the file and what OpenCV said when the model or the
  // class list cannot be loaded, and when the backend / target is not in this OpenCV build.
  // Without a class list path, coco.names beside the model; without an input size, the model's.
  explicit YoloV8Seg(const YoloOptions& params);

  std::vector<Instance> segment(const RgbdImages& images) override;
  std::string name() const override { return "yolo"; }
  // Model, input size, backend and target, for the log at start.
  std::string description() const override;
  const std::vector<std::string>& classNames() const { return class_names_; }

 private:
  YoloOptions params_;
  cv::dnn::Net net_;
  std::vector<std::string> class_names_;
};

}  // namespace ply_slam
