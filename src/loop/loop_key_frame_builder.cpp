#include "ply_slam/loop/loop_key_frame_builder.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

namespace ply_slam {
namespace {

// Whether the pixel (rounded) lies on the mask; false for an empty mask or outside it.
bool onMask(const cv::Mat& mask, const Eigen::Vector2d& pixel) {
  if (mask.empty()) return false;
  const int u = static_cast<int>(std::lround(pixel.x())),
            v = static_cast<int>(std::lround(pixel.y()));
  return u >= 0 && v >= 0 && u < mask.cols && v < mask.rows && mask.at<uint8_t>(v, u) != 0;
}

cv::Mat keptRows(const cv::Mat& rows, const std::vector<bool>& keep) {
  cv::Mat out(0, rows.cols, rows.type());
  for (int r = 0; r < rows.rows; ++r)
    if (keep[r]) out.push_back(rows.row(r));
  return out;
}

// Box of each labelled instance (any class: S_inst drops the moving ones itself).
std::vector<InstanceBox> boxesOfLabels(const KeyFramePacket& packet) {
  std::vector<InstanceBox> boxes;
  if (packet.label_image.empty()) return boxes;
  for (const PacketInstance& instance : packet.instances) {
    const cv::Mat pixels = packet.label_image == instance.id;
    const cv::Rect box = cv::boundingRect(pixels);
    if (box.area() > 0) boxes.push_back({instance.class_name, cv::Rect2d(box)});
  }
  return boxes;
}

}  // namespace

LoopKeyFrameBuilder::LoopKeyFrameBuilder(const LineParams& lines, const PinholeCamera& camera,
                                         const LoopOptions& loop, int mask_dilation_px)
    : lines_(lines),
      lines_enabled_(lines.enabled),
      camera_(camera),
      mover_classes_(loop.dynamic_classes),
      mask_dilation_px_(mask_dilation_px) {}

LoopKeyFrame LoopKeyFrameBuilder::build(const KeyFramePacket& packet) const {
  LoopKeyFrame kf;
  kf.id = packet.id;
  kf.stamp = packet.stamp;
  const cv::Mat movers = moverMask(packet);
  std::vector<bool> keep(packet.keypoints.size());
  for (size_t i = 0; i < keep.size(); ++i) {
    keep[i] = !onMask(movers, packet.keypoints[i]);
    if (!keep[i]) continue;
    kf.keypoints.push_back(packet.keypoints[i]);
    kf.depth.push_back(packet.keypoint_depth[i]);
  }
  kf.orb_descriptors = keptRows(packet.descriptors, keep);
  kf.lbd_descriptors = describeLines(packet.rgb, movers);
  kf.instances = boxesOfLabels(packet);
  return kf;
}

cv::Mat LoopKeyFrameBuilder::moverMask(const KeyFramePacket& packet) const {
  cv::Mat mask;
  if (packet.label_image.empty()) return mask;
  for (const PacketInstance& instance : packet.instances) {
    if (std::find(mover_classes_.begin(), mover_classes_.end(), instance.class_name) ==
        mover_classes_.end())
      continue;
    if (mask.empty()) mask = cv::Mat::zeros(packet.label_image.size(), CV_8UC1);
    mask.setTo(255, packet.label_image == instance.id);
  }
  if (!mask.empty() && mask_dilation_px_ > 0) {
    const int size = 2 * mask_dilation_px_ + 1;
    cv::dilate(mask, mask, cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(size, size)));
  }
  return mask;
}

cv::Mat LoopKeyFrameBuilder::describeLines(const cv::Mat& rgb, const cv::Mat& movers) const {
  if (!lines_enabled_ || rgb.empty()) return cv::Mat();
  cv::Mat gray;
  cv::cvtColor(rgb, gray, cv::COLOR_BGR2GRAY);
  std::vector<LineFeature> lines;
  for (const LineFeature& line : lines_.detect(gray, camera_))
    if (!onMask(movers, 0.5 * (line.raw_start + line.raw_end))) lines.push_back(line);
  return lines_.describe(gray, lines);
}

}  // namespace ply_slam
