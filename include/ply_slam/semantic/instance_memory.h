#pragma once

#include <opencv2/core.hpp>
#include <set>
#include <vector>

#include "ply_slam/semantic/instance.h"
#include "ply_slam/semantic/mask_carrier.h"

namespace ply_slam {

// Segmenters miss a person now and then for a frame or two (blur, a partial view), and a
// missed person's features would go straight into tracking. This keeps the instances judged
// dynamic and, while the segmenter does not see them again, carries their masks to the
// following frames (MaskCarrier) for up to `max_frames` frames.
class InstanceMemory {
 public:
  explicit InstanceMemory(int max_frames) : max_frames_(max_frames) {}

  // The frame's instances plus the remembered dynamic ones it lacks (carried to `gray`).
  std::vector<Instance> complete(const std::vector<Instance>& instances, const cv::Mat& gray);
  // After the frame was judged: which of `instances` (as returned by complete) were dynamic.
  void remember(const std::vector<Instance>& instances, const std::set<int>& dynamic_ids,
                const cv::Mat& gray);

 private:
  struct Remembered {
    Instance instance;
    int age = 0;  // frames since the segmenter last saw it
  };
  int max_frames_;
  int next_id_ = kFirstCarriedId;
  std::vector<Remembered> remembered_;
  std::vector<Remembered> carried_;  // of the frame being judged
  cv::Mat gray_;
  MaskCarrier carrier_;
  static constexpr int kFirstCarriedId = 60000;  // above any segmenter's ids
};

}  // namespace ply_slam
