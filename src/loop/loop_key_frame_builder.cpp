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

}  // namespace

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
  cv::Mat movers;
  readLabels(packet, kf.instances, movers);
  std::vector<bool> keep(packet.keypoints.size());
  for (size_t i = 0; i < keep.size(); ++i) {
    keep[i] = !onMask(movers, packet.keypoints[i]);
    if (!keep[i]) continue;
    kf.keypoints.push_back(packet.keypoints[i]);
    kf.depth.push_back(packet.keypoint_depth[i]);
  }
  kf.orb_descriptors = keptRows(packet.descriptors, keep);
  kf.lbd_descriptors = describeLines(packet.rgb, movers);
  if (movers_out) *movers_out = movers;
  return kf;
}

void LoopKeyFrameBuilder::readLabels(const KeyFramePacket& packet, std::vector<InstanceBox>& boxes,
                                     cv::Mat& movers) const {
  if (packet.label_image.empty()) return;
  for (const PacketInstance& instance : packet.instances) {
    const cv::Mat pixels = packet.label_image == instance.id;  // one pass per instance
    const cv::Rect box = cv::boundingRect(pixels);
    if (box.area() == 0) continue;
    // Every class gets a box (S_inst drops the moving ones itself).
    boxes.push_back({instance.class_name, cv::Rect2d(box)});
    if (std::find(mover_classes_.begin(), mover_classes_.end(), instance.class_name) ==
        mover_classes_.end())
      continue;
    if (movers.empty()) movers = cv::Mat::zeros(packet.label_image.size(), CV_8UC1);
    movers.setTo(255, pixels);
  }
  if (!movers.empty() && mask_dilation_px_ > 0) {
    const int size = 2 * mask_dilation_px_ + 1;
    cv::dilate(movers, movers, cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(size, size)));
  }
}

cv::Mat LoopKeyFrameBuilder::describeLines(const cv::Mat& rgb, const cv::Mat& movers) const {
  if (rgb.empty()) return cv::Mat();
  cv::Mat gray;
  cv::cvtColor(rgb, gray, cv::COLOR_BGR2GRAY);
  std::vector<LineFeature> lines;
  for (const LineFeature& line : lines_.detect(gray, camera_))
    if (!onMask(movers, 0.5 * (line.raw_start + line.raw_end))) lines.push_back(line);
  return lines_.describe(gray, lines);
}

}  // namespace ply_slam
