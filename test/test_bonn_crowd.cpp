// The whole system on a real sensor from another lab among real people: the Bonn RGB-D
// Dynamic `crowd` window (../shared/data/bonn, Xtion, three people walking within a metre),
// YOLOv8-seg 480x640 through OpenCV DNN, the paper's full dynamic rejection, offline; and the
// same window without a segmenter (the Delaunay check over the depth image's surfaces).
#include <gtest/gtest.h>

#include <iostream>

#include "ply_slam/eval/trajectory_metrics.h"
#include "ply_slam/io/tum_sequence.h"
#include "ply_slam/semantic/yolo_v8_seg.h"
#include "ply_slam/system/system.h"
#include "ply_slam/system/system_config.h"
#include "shared_data.h"

namespace ply_slam {
namespace {

TEST(BonnCrowd, OfflineYoloFullTracksAmongPeople) {
  const std::string folder = test::sharedPath("data/bonn/rgbd_bonn_crowd_150_449");
  const std::string model = test::sharedPath("models/yolov8n-seg-480x640.onnx");
  PLY_SLAM_REQUIRE_SHARED(folder);
  PLY_SLAM_REQUIRE_SHARED(model);
  SystemConfig config = loadConfig(std::string(PLY_SLAM_SOURCE_DIR) + "/config/bonn.yaml");
  config.dense.enabled = false;  // the trajectory is what is measured here
  YoloOptions yolo_params = config.segmentation;
  yolo_params.model_path = model;
  yolo_params.class_names_path = test::sharedPath("models/coco.names");
  yolo_params.input_width = 640;
  yolo_params.input_height = 480;
  YoloV8Seg yolo(yolo_params);
  const TumSequence sequence(folder);
  ASSERT_EQ(sequence.size(), 300u);

  System system(config);
  int lost = 0;
  for (size_t i = 0; i < sequence.size(); ++i) {
    const RgbdImages images = sequence.load(i, config.camera.depth_factor);
    lost += system.process(images, yolo.segment(images)).tracking.state != TrackingState::kOk;
  }
  const AteResult ate = computeAte(sequence.groundTruth(), system.cameraTrajectory());
  std::cout << "[ measured ] Bonn crowd 150-449, YOLO 480x640, full: ATE " << ate.translation.rmse
            << " m, lost " << lost << "\n";
  // The offline bound the Bonn issue sets (0.0254 m and no frame lost when written; a changed
  // mask or match moves it by a few mm, and lost frames are counted by scripts/benchmark.sh).
  EXPECT_LE(ate.translation.rmse, 0.030);
}

TEST(BonnCrowd, GeometryAloneTracksAmongPeople) {
  const std::string folder = test::sharedPath("data/bonn/rgbd_bonn_crowd_150_449");
  PLY_SLAM_REQUIRE_SHARED(folder);
  SystemConfig config = loadConfig(std::string(PLY_SLAM_SOURCE_DIR) + "/config/bonn.yaml");
  config.dense.enabled = false;
  config.dynamic.mode = modeWithoutSegmenter(config.dynamic.mode);
  ASSERT_EQ(config.dynamic.mode, DynamicMode::kGeometric);
  const TumSequence sequence(folder);
  System system(config);
  int lost = 0;
  for (size_t i = 0; i < sequence.size(); ++i)
    lost += system.process(sequence.load(i, config.camera.depth_factor)).tracking.state !=
            TrackingState::kOk;
  const AteResult ate = computeAte(sequence.groundTruth(), system.cameraTrajectory());
  std::cout << "[ measured ] Bonn crowd 150-449, no segmenter: ATE " << ate.translation.rmse
            << " m, lost " << lost << "\n";
  // The bound for geometry alone (0.0259 m and no frame lost when written; 0.269 m
  // before the surfaces, when people a metre away were taken for the room).
  EXPECT_LE(ate.translation.rmse, 0.08);
  EXPECT_EQ(lost, 0);
}

}  // namespace
}  // namespace ply_slam
