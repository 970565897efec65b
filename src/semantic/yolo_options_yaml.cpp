#include "ply_slam/semantic/yolo_options_yaml.h"

namespace ply_slam {
namespace {

constexpr EnumWord<DnnBackend> kBackendWords[] = {{DnnBackend::kOpenCv, "opencv"},
                                                  {DnnBackend::kCuda, "cuda"},
                                                  {DnnBackend::kInferenceEngine, "openvino"}};
constexpr EnumWord<DnnTarget> kTargetWords[] = {{DnnTarget::kCpu, "cpu"},
                                                {DnnTarget::kOpenCl, "opencl"},
                                                {DnnTarget::kOpenClFp16, "opencl_fp16"},
                                                {DnnTarget::kCuda, "cuda"},
                                                {DnnTarget::kCudaFp16, "cuda_fp16"}};

}  // namespace

const char* dnnBackendWord(DnnBackend backend) { return wordOf(kBackendWords, backend); }
const char* dnnTargetWord(DnnTarget target) { return wordOf(kTargetWords, target); }

YoloOptions readYoloOptions(ConfigSection s) {
  YoloOptions y;
  s.read("model", y.model_path);
  s.read("classes", y.class_names_path);
  s.readInRange("input_width", y.input_width, 0, 8192);
  s.readInRange("input_height", y.input_height, 0, 8192);
  if ((y.input_width == 0) != (y.input_height == 0))
    s.fail("input_width", "and input_height are given together (or both 0: the model's own)");
  s.readPositive("score_threshold", y.score_threshold);
  s.readPositive("nms_threshold", y.nms_threshold);
  s.readPositive("mask_threshold", y.mask_threshold);
  if (y.score_threshold >= 1.f) s.fail("score_threshold", "must be < 1");
  if (y.nms_threshold > 1.f) s.fail("nms_threshold", "must be <= 1");
  if (y.mask_threshold >= 1.f) s.fail("mask_threshold", "must be < 1");
  s.readWord("backend", y.backend, kBackendWords, "must be opencv, cuda or openvino");
  s.readWord("target", y.target, kTargetWords,
             "must be cpu, opencl, opencl_fp16, cuda or cuda_fp16");
  s.readInRange("live_threads", y.live_threads, 0, 256);
  s.rejectUnknownKeys();
  return y;
}

}  // namespace ply_slam
