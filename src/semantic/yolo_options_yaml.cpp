#include "ply_slam/semantic/yolo_options_yaml.h"

namespace ply_slam {

YoloOptions readYoloOptions(ConfigSection s) {
  YoloOptions y;
  s.read("model", y.model_path);
  s.read("classes", y.class_names_path);
  s.readPositive("input_width", y.input_width);
  s.readPositive("input_height", y.input_height);
  s.readPositive("score_threshold", y.score_threshold);
  s.readPositive("nms_threshold", y.nms_threshold);
  s.readPositive("mask_threshold", y.mask_threshold);
  if (y.score_threshold >= 1.f) s.fail("score_threshold", "must be < 1");
  if (y.nms_threshold > 1.f) s.fail("nms_threshold", "must be <= 1");
  if (y.mask_threshold >= 1.f) s.fail("mask_threshold", "must be < 1");
  s.rejectUnknownKeys();
  return y;
}

}  // namespace ply_slam
