// YOLOv8-seg through OpenCV DNN on the real models in ../shared/models and the shared walkers
// frames, whose ground-truth masks give the answer.
#include <gtest/gtest.h>

#include <algorithm>
#include <iostream>
#include <opencv2/core.hpp>
#include <opencv2/dnn.hpp>
#include <vector>

#include "ply_slam/io/tum_sequence.h"
#include "ply_slam/semantic/mask_folder_segmenter.h"
#include "ply_slam/semantic/onnx_input_shape.h"
#include "ply_slam/semantic/yolo_v8_seg.h"
#include "shared_data.h"

namespace ply_slam {
namespace {

const char* const kWalkers = "data/dynamic/fr1_rpy_150_349_walkers";

double iou(const cv::Mat& a, const cv::Mat& b) {
  const double inter = cv::countNonZero(a & b), uni = cv::countNonZero(a | b);
  return uni > 0 ? inter / uni : 0.0;
}

// The YOLOv8-seg target: over frames where a walker covers > 2 % of the image, the median IoU of
// its ground-truth mask with the best-overlapping person mask is >= 0.6 (every 20th frame).
void expectWalkersFound(const std::string& model, int width, int height) {
  const std::string folder = test::sharedPath(kWalkers);
  const std::string model_path = test::sharedPath("models/" + model);
  PLY_SLAM_REQUIRE_SHARED(folder);
  PLY_SLAM_REQUIRE_SHARED(model_path);
  YoloOptions params;
  params.model_path = model_path;
  params.class_names_path = test::sharedPath("models/coco.names");
  params.input_width = width;
  params.input_height = height;
  YoloV8Seg yolo(params);
  ASSERT_EQ(yolo.classNames().size(), 80u);
  const TumSequence sequence(folder);
  MaskFolderSegmenter truth(folder);
  std::vector<double> ious;
  for (size_t frame = 0; frame < sequence.size(); frame += 20) {
    const RgbdImages images = sequence.load(frame, 5000.0);
    const auto found = yolo.segment(images);
    for (const auto& instance : found) {
      ASSERT_EQ(instance.mask.size(), images.rgb.size());
      ASSERT_EQ(instance.mask.type(), CV_8UC1);
    }
    for (const auto& walker : truth.segment(images)) {
      if (cv::countNonZero(walker.mask) < 0.02 * walker.mask.total()) continue;
      double best = 0.0;
      for (const auto& instance : found)
        if (instance.class_name == "person") best = std::max(best, iou(instance.mask, walker.mask));
      ious.push_back(best);
    }
  }
  ASSERT_GE(ious.size(), 5u);
  std::sort(ious.begin(), ious.end());
  const double median = ious[ious.size() / 2];
  std::cout << "[ measured ] " << model << ": median person IoU " << median << " over "
            << ious.size() << " walker views, lowest " << ious.front() << "\n";
  EXPECT_GE(median, 0.6);
}

TEST(YoloV8Seg, Model640x640) { expectWalkersFound("yolov8n-seg-640x640.onnx", 640, 640); }
TEST(YoloV8Seg, Model480x640) { expectWalkersFound("yolov8n-seg-480x640.onnx", 640, 480); }
TEST(YoloV8Seg, Model320x320) { expectWalkersFound("yolov8n-seg-320x320.onnx", 320, 320); }

// Input size 0 (the configs' default) takes the export's own, read from the ONNX file.
TEST(YoloV8Seg, InputSizeZeroTakesTheModelsOwn) {
  const std::string model_path = test::sharedPath("models/yolov8n-seg-480x640.onnx");
  PLY_SLAM_REQUIRE_SHARED(model_path);
  YoloOptions params;
  params.model_path = model_path;
  params.input_width = 0;
  params.input_height = 0;
  const YoloV8Seg yolo(params);
  EXPECT_NE(yolo.description().find("640x480"), std::string::npos) << yolo.description();
}

// OpenCV falls back to the CPU silently; a backend this build lacks is refused, naming what it has.
TEST(YoloV8Seg, AnUnavailableBackendIsRefusedNamingTheAvailableOnes) {
  const std::string model_path = test::sharedPath("models/yolov8n-seg-320x320.onnx");
  PLY_SLAM_REQUIRE_SHARED(model_path);
  bool has_cuda = false;
  for (const auto& pair : cv::dnn::getAvailableBackends())
    has_cuda = has_cuda || pair.first == cv::dnn::DNN_BACKEND_CUDA;
  if (has_cuda) GTEST_SKIP() << "this OpenCV build has CUDA";
  YoloOptions params;
  params.model_path = model_path;
  params.backend = DnnBackend::kCuda;
  params.target = DnnTarget::kCuda;
  try {
    YoloV8Seg yolo(params);
    FAIL() << "cuda/cuda accepted";
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("cuda"), std::string::npos) << what;
    EXPECT_NE(what.find("opencv/cpu"), std::string::npos) << what;
  }
}

TEST(YoloV8Seg, MissingModelIsNamed) {
  YoloOptions params;
  params.model_path = "/nonexistent/model.onnx";
  try {
    YoloV8Seg yolo(params);
    FAIL() << "missing model accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/model.onnx"), std::string::npos);
  }
}

TEST(YoloV8Seg, WrongInputSizeIsExplained) {
  const std::string model_path = test::sharedPath("models/yolov8n-seg-320x320.onnx");
  PLY_SLAM_REQUIRE_SHARED(model_path);
  YoloOptions params;
  params.model_path = model_path;
  params.class_names_path = test::sharedPath("models/coco.names");
  params.input_width = params.input_height = 640;  // the export is 320 x 320
  try {
    YoloV8Seg yolo(params);
    RgbdImages images;
    images.rgb = cv::Mat(480, 640, CV_8UC3, cv::Scalar(90, 120, 150));
    yolo.segment(images);
    FAIL() << "a 640 x 640 input into a 320 x 320 export went through";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("input size"), std::string::npos) << e.what();
  }
}

// The shared model files are named HxW and --input takes WxH: 480x640 into the 640-wide export
// has the same area and ran with wrong anchors (IoU 0.59 instead of 0.91). The size is read
// from the model now and a mismatch named at load.
TEST(YoloV8Seg, TransposedInputSizeIsRefusedAtLoad) {
  const std::string model_path = test::sharedPath("models/yolov8n-seg-480x640.onnx");
  PLY_SLAM_REQUIRE_SHARED(model_path);
  const auto shapeOf = [](const std::string& path) {
    return onnxInputShape(readOnnxModelFile(path), path);
  };
  EXPECT_EQ(shapeOf(model_path), (std::vector<std::int64_t>{1, 3, 480, 640}));
  EXPECT_EQ(shapeOf(test::sharedPath("models/yolov8n-seg-320x320.onnx")),
            (std::vector<std::int64_t>{1, 3, 320, 320}));
  YoloOptions params;
  params.model_path = model_path;
  params.class_names_path = test::sharedPath("models/coco.names");
  params.input_width = 480;
  params.input_height = 640;
  try {
    YoloV8Seg yolo(params);
    FAIL() << "480x640 (WxH) accepted for the 640-wide export";
  } catch (const std::runtime_error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(model_path), std::string::npos) << message;
    EXPECT_NE(message.find("640x480"), std::string::npos) << message;
  }
  params.input_width = 640;
  params.input_height = 480;
  EXPECT_NO_THROW(YoloV8Seg{params});
}

TEST(YoloV8Seg, AFileThatIsNoOnnxModelIsNamed) {
  const std::string path = std::string(PLY_SLAM_SOURCE_DIR) + "/config/tum_fr1.yaml";
  std::vector<std::int64_t> shape;
  try {
    shape = onnxInputShape(readOnnxModelFile(path), path);
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
  EXPECT_TRUE(shape.empty());  // no shape read from what is no model
  EXPECT_THROW(readOnnxModelFile("/nonexistent/model.onnx"), std::runtime_error);
}

}  // namespace
}  // namespace ply_slam
