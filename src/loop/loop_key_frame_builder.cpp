#include "ply_slam/loop/loop_key_frame_builder.h"

#include <opencv2/imgproc.hpp>

#include "ply_slam/loop/moving_pixels.h"

namespace ply_slam {

LoopKeyFrameBuilder::LoopKeyFrameBuilder(const LineOptions& lines, const PinholeCamera& camera,
                                         const LoopOptions& loop, int mask_dilation_px)
    : lines_(lines),
      camera_(camera),
      mover_classes_(loop.dynamic_classes),
      mask_dilation_px_(mask_dilation_px) {}

LoopKeyFrame LoopKeyFrameBuilder::build(const KeyFramePacket& packet, cv::Mat* movers_out) const {
  LoopKeyFrame kf;
  kf.id = packet.id;
  kf.stamp = packet.stamp;
  kf.instances = boxesOf(packet);
  const cv::Mat movers =
      movingPixels(packet.label_image, packet.instances, mover_classes_, mask_dilation_px_);
  const std::vector<bool> keep = offMask(packet.keypoints, movers);
  for (size_t i = 0; i < keep.size(); ++i) {
    if (!keep[i]) continue;
    kf.keypoints.push_back(packet.keypoints[i]);
    kf.depth.push_back(packet.keypoint_depth[i]);
  }
  kf.orb_descriptors = keptRows(packet.descriptors, keep);
  kf.lbd_descriptors = describeLines(packet.rgb, movers);
  if (movers_out) *movers_out = movers;
  return kf;
}

std::vector<InstanceBox> LoopKeyFrameBuilder::boxesOf(const KeyFramePacket& packet) {
  std::vector<InstanceBox> boxes;
  if (packet.label_image.empty()) return boxes;
  // Every class gets a box (S_inst drops the moving ones itself).
  for (const PacketInstance& instance : packet.instances)
    if (const cv::Rect box = cv::boundingRect(packet.label_image == instance.id); box.area() > 0)
      boxes.push_back({instance.class_name, cv::Rect2d(box)});
  return boxes;
}

cv::Mat LoopKeyFrameBuilder::describeLines(const cv::Mat& rgb, const cv::Mat& movers) const {
  if (rgb.empty()) return cv::Mat();
  cv::Mat gray;
  cv::cvtColor(rgb, gray, cv::COLOR_BGR2GRAY);
  const std::vector<LineFeature> detected = lines_.detect(gray, camera_);
  std::vector<Eigen::Vector2d> middles;
  for (const LineFeature& line : detected) middles.push_back(0.5 * (line.raw_start + line.raw_end));
  const std::vector<bool> keep = offMask(middles, movers);
  std::vector<LineFeature> lines;
  for (size_t i = 0; i < detected.size(); ++i)
    if (keep[i]) lines.push_back(detected[i]);
  return lines_.describe(gray, lines);
}

}  // namespace ply_slam
