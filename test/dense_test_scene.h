#pragma once

// A synthetic room for the dense-map tests: a wall facing the camera at kWallDepth and,
// optionally, a person (instance 1) standing in front of it at kWalkerDepth.
#include <memory>
#include <opencv2/core.hpp>

#include "ply_slam/map/key_frame_packet.h"
#include "ply_slam/synth/synthetic_sequence.h"
#include "ply_slam/system/system_config.h"

namespace ply_slam::test {

// Depths fall mid-voxel for 5 cm voxels, so no point lies on a voxel boundary.
constexpr double kWallDepth = 3.02;
constexpr double kWalkerDepth = 1.52;
const cv::Rect kWalkerPixels(60, 20, 40, 90);  // columns 60..99, rows 20..109

// The synthetic camera at a quarter of its size (160x120), so that the tests stay fast.
inline PinholeCamera denseTestCamera() {
  PinholeCamera camera = syntheticCamera();
  for (double* f : {&camera.fx, &camera.fy, &camera.cx, &camera.cy}) *f /= 4.0;
  camera.width /= 4;
  camera.height /= 4;
  return camera;
}

// Dense parameters of the tests: every `stride`-th pixel, voxels of `voxel_size`.
inline DenseOptions denseTestParams(int stride, double voxel_size) {
  DenseOptions p;
  p.stride = stride;
  p.voxel_size = voxel_size;
  p.min_depth = 0.3;
  p.max_depth = 4.0;
  p.octree_resolution = 0.05;
  p.octree_occupancy = 0.5;  // one hit makes a voxel occupied
  return p;
}

// `walker`: the person stands there; `dynamic`: it is marked moving (mask and instance flag).
inline std::shared_ptr<KeyFramePacket> wallPacket(long id, const Eigen::Vector3d& camera_position,
                                                  bool walker, bool dynamic) {
  auto packet = std::make_shared<KeyFramePacket>();
  packet->id = id;
  packet->frame_id = id;
  packet->stamp = id;
  packet->camera = denseTestCamera();
  packet->T_wc.translation() = camera_position;
  const cv::Size size(packet->camera.width, packet->camera.height);
  // The wall is the plane z = kWallDepth of the world; the camera looks along +z.
  packet->depth = cv::Mat(size, CV_32FC1, cv::Scalar(kWallDepth - camera_position.z()));
  packet->rgb = cv::Mat(size, CV_8UC3, cv::Scalar(200, 180, 160));
  if (walker) {
    packet->depth(kWalkerPixels).setTo(kWalkerDepth - camera_position.z());
    packet->rgb(kWalkerPixels).setTo(cv::Scalar(0, 0, 255));
    packet->label_image = cv::Mat::zeros(size, CV_16UC1);
    packet->label_image(kWalkerPixels).setTo(1);
    packet->instances.push_back({1, "person", 0.9f, dynamic});
    if (dynamic) {
      packet->dynamic_mask = cv::Mat::zeros(size, CV_8UC1);
      packet->dynamic_mask(kWalkerPixels).setTo(255);
    }
  }
  return packet;
}

}  // namespace ply_slam::test
