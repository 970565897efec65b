#include "ply_slam/semantic/yolo_v8_seg.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <utility>

#include "ply_slam/io/input_file.h"
#include "ply_slam/semantic/onnx_input_shape.h"
#include "ply_slam/semantic/yolo_options_yaml.h"

namespace ply_slam {
namespace {

constexpr int kBoxRows = 4;  // cx, cy, w, h in input pixels
constexpr int kMaskCoefficients = 32;

// How the image was placed into the network input: scaled by `scale`, shifted by `offset`.
struct Letterbox {
  double scale = 1.0;
  cv::Point2d offset;
};

Letterbox letterbox(const cv::Mat& bgr, int width, int height, cv::Mat& input) {
  Letterbox lb;
  lb.scale =
      std::min(static_cast<double>(width) / bgr.cols, static_cast<double>(height) / bgr.rows);
  const int w = static_cast<int>(std::round(bgr.cols * lb.scale));
  const int h = static_cast<int>(std::round(bgr.rows * lb.scale));
  lb.offset = {(width - w) / 2.0, (height - h) / 2.0};
  input = cv::Mat(height, width, CV_8UC3, cv::Scalar(114, 114, 114));
  cv::Mat resized;
  cv::resize(bgr, resized, {w, h}, 0, 0, cv::INTER_LINEAR);
  resized.copyTo(input(cv::Rect(static_cast<int>(std::floor(lb.offset.x)),
                                static_cast<int>(std::floor(lb.offset.y)), w, h)));
  lb.offset = {std::floor(lb.offset.x), std::floor(lb.offset.y)};
  return lb;
}

std::vector<std::string> readClassNames(const std::string& path) {
  refuseSpecialFile(path);
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot read the class names");
  std::vector<std::string> names;
  for (std::string line; std::getline(in, line);) {
    while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
    if (!line.empty()) names.push_back(line);
  }
  if (names.empty()) throw std::runtime_error(path + ": no class names");
  return names;
}

// A fixed-size export runs on any input of its area: 480x640 into a 640x480 export gives
// boxes and masks from the wrong anchors (person IoU 0.59 instead of 0.91) without an error.
// A size of 0 takes the export's own.
void resolveInputSize(YoloOptions& params, const std::vector<std::int64_t>& shape) {
  const bool fixed = shape.size() == 4 && shape[2] > 0 && shape[3] > 0;
  if (params.input_width == 0) {
    if (!fixed)
      throw std::runtime_error(params.model_path +
                               ": the model has no fixed input size; give it (--input WxH, or "
                               "segmentation.input_width and input_height in the config)");
    params.input_width = static_cast<int>(shape[3]);
    params.input_height = static_cast<int>(shape[2]);
    return;
  }
  if (!fixed) return;  // dynamic: any size
  const std::int64_t height = shape[2], width = shape[3];
  if (width == params.input_width && height == params.input_height) return;
  throw std::runtime_error(params.model_path + ": the model's input size is " +
                           std::to_string(width) + "x" + std::to_string(height) +
                           " (width x height), not the " + std::to_string(params.input_width) +
                           "x" + std::to_string(params.input_height) +
                           " asked for (--input WxH, or segmentation.input_width and "
                           "input_height in the config; 0 takes the model's own)");
}

// Our config's backends and targets and OpenCV's for them: one table each, read both ways.
constexpr std::pair<DnnBackend, cv::dnn::Backend> kBackends[] = {
    {DnnBackend::kOpenCv, cv::dnn::DNN_BACKEND_OPENCV},
    {DnnBackend::kCuda, cv::dnn::DNN_BACKEND_CUDA},
    {DnnBackend::kInferenceEngine, cv::dnn::DNN_BACKEND_INFERENCE_ENGINE}};
constexpr std::pair<DnnTarget, cv::dnn::Target> kTargets[] = {
    {DnnTarget::kCpu, cv::dnn::DNN_TARGET_CPU},
    {DnnTarget::kOpenCl, cv::dnn::DNN_TARGET_OPENCL},
    {DnnTarget::kOpenClFp16, cv::dnn::DNN_TARGET_OPENCL_FP16},
    {DnnTarget::kCuda, cv::dnn::DNN_TARGET_CUDA},
    {DnnTarget::kCudaFp16, cv::dnn::DNN_TARGET_CUDA_FP16}};

template <typename Ours, typename Theirs, size_t N>
Theirs openCvOf(const std::pair<Ours, Theirs> (&table)[N], Ours ours) {
  for (const auto& [o, theirs] : table)
    if (o == ours) return theirs;
  return table[0].second;
}

// "opencv/cpu" for a pair this config can name, "" for the others (Vulkan, Myriad, ...).
std::string pairWord(cv::dnn::Backend b, cv::dnn::Target t) {
  for (const auto& [backend, cv_backend] : kBackends)
    for (const auto& [target, cv_target] : kTargets)
      if (cv_backend == b && cv_target == t)
        return std::string(dnnBackendWord(backend)) + "/" + dnnTargetWord(target);
  return "";
}

// OpenCV falls back to the CPU without a word when a backend or target is missing: a robot with
// a GPU would run on its CPU and never know. Refused here, naming what this build and machine have.
void requireAvailable(const YoloOptions& params) {
  const auto wanted =
      std::make_pair(openCvOf(kBackends, params.backend), openCvOf(kTargets, params.target));
  std::string available;
  for (const auto& pair : cv::dnn::getAvailableBackends()) {
    if (pair == wanted) return;
    const std::string word = pairWord(pair.first, pair.second);
    if (!word.empty()) available += (available.empty() ? "" : ", ") + word;
  }
  throw std::runtime_error(std::string("segmentation: backend ") + dnnBackendWord(params.backend) +
                           " with target " + dnnTargetWord(params.target) +
                           " is not available in this OpenCV build on this machine (OpenCV " +
                           CV_VERSION + " has: " + (available.empty() ? "none" : available) +
                           "); set segmentation.backend and segmentation.target to one of them");
}

// The anchors whose best class score reaches the threshold: box (input pixels), score, class.
struct Detections {
  std::vector<cv::Rect2d> boxes;
  std::vector<float> scores;
  std::vector<int> classes, anchor_of;
};

Detections detect(const cv::Mat& table, int num_classes, float score_threshold) {
  Detections d;
  for (int a = 0; a < table.cols; ++a) {
    int best_class = 0;
    float best = 0.f;
    for (int c = 0; c < num_classes; ++c) {
      const float s = table.at<float>(kBoxRows + c, a);
      if (s > best) {
        best = s;
        best_class = c;
      }
    }
    if (best < score_threshold) continue;
    const float cx = table.at<float>(0, a), cy = table.at<float>(1, a);
    const float w = table.at<float>(2, a), h = table.at<float>(3, a);
    d.boxes.emplace_back(cx - w / 2, cy - h / 2, w, h);
    d.scores.push_back(best);
    d.classes.push_back(best_class);
    d.anchor_of.push_back(a);
  }
  return d;
}

// Class-aware NMS: boxes of different classes never suppress each other.
// (OpenCV 4.6 has no NMSBoxesBatched: each class is shifted far away from the others.)
std::vector<int> keptByNms(const Detections& d, const YoloOptions& params) {
  std::vector<cv::Rect2d> shifted = d.boxes;
  const double shift = 4.0 * std::max(params.input_width, params.input_height);
  for (size_t i = 0; i < shifted.size(); ++i) shifted[i].x += d.classes[i] * shift;
  std::vector<int> keep;
  cv::dnn::NMSBoxes(shifted, d.scores, params.score_threshold, params.nms_threshold, keep);
  return keep;
}

// An instance's mask in the image from its 32 coefficients and the prototype masks.
class MaskDecoder {
 public:
  MaskDecoder(const cv::Mat& protos, const YoloOptions& params, const Letterbox& lb,
              const cv::Size& image_size)
      : ph_(protos.size[2]),
        pw_(protos.size[3]),
        proto_matrix_(kMaskCoefficients, ph_ * pw_, CV_32F,
                      const_cast<float*>(protos.ptr<float>())),
        proto_scale_(static_cast<double>(pw_) / params.input_width),
        // sigmoid(x) > t  <=>  x > log(t / (1 - t)): threshold the logits directly.
        logit_threshold_(std::log(params.mask_threshold / (1.f - params.mask_threshold))),
        lb_(lb),
        image_size_(image_size) {}

  // Empty when the box leaves the image or no pixel passes the threshold.
  cv::Mat decode(const cv::Mat& table, int num_classes, int anchor, const cv::Rect2d& b) const {
    cv::Mat coefficients(1, kMaskCoefficients, CV_32F);
    for (int m = 0; m < kMaskCoefficients; ++m)
      coefficients.at<float>(0, m) = table.at<float>(kBoxRows + num_classes + m, anchor);
    const cv::Mat logits = cv::Mat(coefficients * proto_matrix_).reshape(1, ph_);
    // The box in the image, and the same box in prototype and input coordinates.
    const cv::Rect2d in_image((b.x - lb_.offset.x) / lb_.scale, (b.y - lb_.offset.y) / lb_.scale,
                              b.width / lb_.scale, b.height / lb_.scale);
    const cv::Rect image_box = cv::Rect(in_image) & cv::Rect(cv::Point(0, 0), image_size_);
    if (image_box.area() <= 0) return cv::Mat();
    // Sample the prototype logits straight at the box's image pixels (pixel centres):
    // proto = (image * letterbox scale + letterbox offset) * proto_scale.
    const double s_img = lb_.scale * proto_scale_;
    const cv::Matx23d image_to_proto(
        s_img, 0, (image_box.x + 0.5) * s_img + lb_.offset.x * proto_scale_ - 0.5, 0, s_img,
        (image_box.y + 0.5) * s_img + lb_.offset.y * proto_scale_ - 0.5);
    cv::Mat box_logits;
    cv::warpAffine(logits, box_logits, image_to_proto, image_box.size(),
                   cv::INTER_LINEAR | cv::WARP_INVERSE_MAP, cv::BORDER_REPLICATE);
    cv::Mat mask = cv::Mat::zeros(image_size_, CV_8UC1);
    mask(image_box).setTo(255, box_logits > logit_threshold_);
    if (cv::countNonZero(mask) == 0) return cv::Mat();
    return mask;
  }

 private:
  int ph_, pw_;
  cv::Mat proto_matrix_;
  double proto_scale_;
  float logit_threshold_;
  Letterbox lb_;
  cv::Size image_size_;
};

}  // namespace

YoloV8Seg::YoloV8Seg(const YoloOptions& params) : params_(params) {
  if (params_.model_path.empty())
    throw std::runtime_error("no YOLOv8-seg model given (config segmentation.model or --model)");
  if (!std::filesystem::exists(params_.model_path))
    throw std::runtime_error(params_.model_path + ": YOLOv8-seg model file missing");
  const std::string bytes = readOnnxModelFile(params_.model_path);  // the net and its shape
  try {
    net_ = cv::dnn::readNetFromONNX(bytes.data(), bytes.size());
  } catch (const cv::Exception& e) {
    throw std::runtime_error(params_.model_path + ": OpenCV cannot load the model: " + e.what());
  }
  if (net_.empty()) throw std::runtime_error(params_.model_path + ": OpenCV loaded an empty net");
  resolveInputSize(params_, onnxInputShape(bytes, params_.model_path));
  requireAvailable(params_);
  net_.setPreferableBackend(openCvOf(kBackends, params_.backend));
  net_.setPreferableTarget(openCvOf(kTargets, params_.target));
  if (params_.class_names_path.empty())  // the usual layout: coco.names beside the model
    params_.class_names_path =
        (std::filesystem::path(params_.model_path).parent_path() / "coco.names").string();
  class_names_ = readClassNames(params_.class_names_path);
}

std::vector<Instance> YoloV8Seg::segment(const RgbdImages& images) {
  const cv::Mat& bgr = images.rgb;
  if (bgr.empty() || bgr.type() != CV_8UC3)
    throw std::runtime_error("YOLOv8-seg needs an 8-bit colour image");
  cv::Mat input;
  const Letterbox lb = letterbox(bgr, params_.input_width, params_.input_height, input);
  net_.setInput(cv::dnn::blobFromImage(input, 1.0 / 255.0, cv::Size(), cv::Scalar(), true, false));
  std::vector<cv::Mat> outs;
  try {
    net_.forward(outs, std::vector<std::string>{"output0", "output1"});
  } catch (const cv::Exception& e) {
    throw std::runtime_error(params_.model_path + ": forward pass failed (is the input size " +
                             std::to_string(params_.input_width) + "x" +
                             std::to_string(params_.input_height) + " the export's?): " + e.what());
  }
  // output0: [1, 4 + classes + 32, anchors]; output1: [1, 32, H/4, W/4].
  const cv::Mat& det = outs[0];
  const cv::Mat& protos = outs[1];
  const int rows = det.size[1], anchors = det.size[2];
  const int num_classes = rows - kBoxRows - kMaskCoefficients;
  if (det.dims != 3 || protos.dims != 4 || num_classes <= 0 ||
      num_classes != static_cast<int>(class_names_.size()))
    throw std::runtime_error(params_.model_path + ": unexpected output shapes for " +
                             std::to_string(class_names_.size()) + " classes");
  const cv::Mat table(rows, anchors, CV_32F, const_cast<float*>(det.ptr<float>()));
  const Detections found = detect(table, num_classes, params_.score_threshold);
  const MaskDecoder masks(protos, params_, lb, bgr.size());
  std::vector<Instance> instances;
  int next_id = 1;
  for (int k : keptByNms(found, params_)) {
    const cv::Mat mask = masks.decode(table, num_classes, found.anchor_of[k], found.boxes[k]);
    if (mask.empty()) continue;
    instances.push_back({next_id++, class_names_[found.classes[k]], found.scores[k], mask});
  }
  return instances;
}

std::string YoloV8Seg::description() const {
  return "YOLOv8-seg " + params_.model_path + " " + std::to_string(params_.input_width) + "x" +
         std::to_string(params_.input_height) + ", backend " + dnnBackendWord(params_.backend) +
         ", target " + dnnTargetWord(params_.target);
}

}  // namespace ply_slam
