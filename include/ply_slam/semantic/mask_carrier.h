#pragma once

#include <opencv2/core.hpp>
#include <vector>

#include "ply_slam/semantic/instance.h"

namespace ply_slam {

struct MaskCarrierParams {
  int samples_per_instance = 40;  // corners tracked inside each mask
  int margin_px = 4;              // extra dilation on top of the spread of the flow
};

// Moves instance masks from the frame they were segmented in to a later frame: sparse
// Lucas-Kanade flow of corners inside each mask, the mask shifted by their median flow and
// dilated by how much the flows disagree (a person turning or the camera rotating), so the
// carried mask covers the object rather than trailing it.
class MaskCarrier {
 public:
  explicit MaskCarrier(const MaskCarrierParams& params = {}) : params_(params) {}

  // from_gray / to_gray: 8UC1 images of one size; instances' masks of that size.
  std::vector<Instance> carry(const std::vector<Instance>& instances, const cv::Mat& from_gray,
                              const cv::Mat& to_gray) const;

 private:
  MaskCarrierParams params_;
};

}  // namespace ply_slam
