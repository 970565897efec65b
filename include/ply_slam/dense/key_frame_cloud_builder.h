#pragma once

#include <opencv2/core.hpp>

#include "ply_slam/common/pinhole_camera.h"
#include "ply_slam/dense/class_palette.h"
#include "ply_slam/dense/dense_options.h"
#include "ply_slam/dense/key_frame_cloud.h"
#include "ply_slam/map/key_frame_packet.h"

namespace ply_slam {

// KeyFramePacket -> coloured, labelled point cloud in the camera frame: every `stride`-th
// pixel with depth in [min_depth, max_depth], except those of dynamic instances (the packet's
// dynamic mask and the instances marked dynamic, dilated by dilation_px), voxel-filtered; and
// the rays to the pixels beyond max_depth (up to the camera's max_depth) for free space.
// Raw pixels are undistorted with the packet's camera (a table computed once per camera and
// cached, so one builder must not be shared between threads).
class KeyFrameCloudBuilder {
 public:
  KeyFrameCloudBuilder(const DenseOptions& params, ClassPalette palette);

  // `tag_mask` (8UC1 of the image size, may be empty): evaluation only, fills cloud.tags.
  // Throws std::invalid_argument naming the fault for a packet that cannot be used (empty or
  // mistyped images, sizes that differ from each other or from the camera).
  KeyFrameCloud build(const KeyFramePacket& packet, const cv::Mat& tag_mask = cv::Mat()) const;

 private:
  // Normalised image coordinates (x/z, y/z) of each raw pixel, CV_32FC2.
  const cv::Mat& rayTable(const PinholeCamera& camera) const;
  cv::Mat excludedPixels(const KeyFramePacket& packet) const;

  DenseOptions params_;
  ClassPalette palette_;
  mutable cv::Mat rays_;
  mutable PinholeCamera rays_camera_;
};

}  // namespace ply_slam
