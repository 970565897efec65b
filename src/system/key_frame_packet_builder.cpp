#include "ply_slam/system/key_frame_packet_builder.h"

#include <algorithm>

namespace ply_slam {

KeyFramePacket makeSparseKeyFramePacket(const KeyFrame& keyframe, const PinholeCamera& camera) {
  KeyFramePacket packet;
  packet.id = keyframe.id;
  packet.frame_id = keyframe.frame_id;
  packet.stamp = keyframe.stamp;
  packet.T_wc = keyframe.T_wc();
  packet.camera = camera;

  const FrameFeatures& f = keyframe.features;
  packet.keypoints = f.undistorted;
  packet.keypoint_depth = f.depth;
  packet.keypoint_level.reserve(f.size());
  for (size_t i = 0; i < f.size(); ++i) packet.keypoint_level.push_back(f.level(i));
  packet.descriptors = f.descriptors.clone();
  packet.keypoint_landmark.assign(f.size(), -1);
  for (size_t i = 0; i < keyframe.map_points.size() && i < f.size(); ++i) {
    const auto& mp = keyframe.map_points[i];
    if (!mp || mp->bad) continue;
    packet.keypoint_landmark[i] = mp->id;
    packet.points.push_back({mp->id, mp->position});
  }
  for (const auto& ml : keyframe.map_lines)
    if (ml && !ml->bad) packet.lines.push_back({ml->id, ml->start, ml->end});
  return packet;
}

KeyFrameSegmentation segmentationOf(const std::vector<Instance>& instances,
                                    const std::set<int>& dynamic_ids, const cv::Mat& dynamic_mask,
                                    const cv::Size& size) {
  KeyFrameSegmentation segmentation;
  segmentation.dynamic_mask = dynamic_mask;
  if (!instances.empty()) {
    segmentation.label_image = cv::Mat::zeros(size, CV_16UC1);
    // Larger instances first, so a smaller one in front keeps its pixels where they overlap.
    std::vector<std::pair<int, const Instance*>> order;  // (area, instance)
    for (const auto& instance : instances)
      order.push_back({cv::countNonZero(instance.mask), &instance});
    std::stable_sort(order.begin(), order.end(),
                     [](const auto& a, const auto& b) { return a.first > b.first; });
    for (const auto& [area, instance] : order) {
      const int id = std::clamp(instance->id, 1, 65535);
      segmentation.label_image.setTo(id, instance->mask);
      segmentation.instances.push_back(
          {id, instance->class_name, instance->score, dynamic_ids.count(instance->id) > 0});
    }
  }
  return segmentation;
}

std::vector<KeyFramePacket> sparseKeyFramePackets(const Map& map, const PinholeCamera& camera) {
  std::lock_guard<std::mutex> lock(map.updateMutex());
  std::vector<KeyFramePacket> packets;
  for (const auto& kf : map.keyFrames()) packets.push_back(makeSparseKeyFramePacket(*kf, camera));
  return packets;
}

KeyFramePacket makeKeyFramePacket(const KeyFrame& keyframe, const PinholeCamera& camera,
                                  const RgbdImages& images,
                                  const KeyFrameSegmentation& segmentation) {
  KeyFramePacket packet = makeSparseKeyFramePacket(keyframe, camera);
  packet.rgb = images.rgb;
  packet.depth = images.depth;
  packet.label_image = segmentation.label_image;
  packet.instances = segmentation.instances;
  packet.dynamic_mask = segmentation.dynamic_mask;
  return packet;
}

}  // namespace ply_slam
