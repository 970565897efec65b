#pragma once

#include <opencv2/core.hpp>

#include "ply_slam/common/pinhole_camera.h"
#include "ply_slam/features/line_extractor.h"
#include "ply_slam/features/line_options.h"
#include "ply_slam/loop/loop_detector.h"
#include "ply_slam/map/key_frame_packet.h"

namespace ply_slam {

// What place recognition keeps of a keyframe, from the packet the mapping side receives: its
// ORB features with depth, the LBD descriptors of the lines in its image and its instances'
// boxes. Features and lines on instances of moving classes are left out (movingPixels). Lines
// are described whether or not tracking uses them (LineOptions::enabled): the point-line score
// needs them, and once per keyframe they cost what tracking with lines costs on every frame.
class LoopKeyFrameBuilder {
 public:
  LoopKeyFrameBuilder(const LineOptions& lines, const PinholeCamera& camera,
                      const LoopOptions& loop, int mask_dilation_px);

  // `movers` (optional): the pixels left out, those of instances of moving classes, dilated
  // (8UC1, non-zero on them; empty when there are none).
  LoopKeyFrame build(const KeyFramePacket& packet, cv::Mat* movers = nullptr) const;

 private:
  // The box of each labelled instance.
  static std::vector<InstanceBox> boxesOf(const KeyFramePacket& packet);
  // LBD descriptors of the image's lines whose middle is off the movers.
  cv::Mat describeLines(const cv::Mat& rgb, const cv::Mat& movers) const;

  LineExtractor lines_;
  PinholeCamera camera_;
  std::vector<std::string> mover_classes_;
  int mask_dilation_px_;
};

}  // namespace ply_slam
