#pragma once

#include <opencv2/core.hpp>
#include <vector>

#include "ply_slam/semantic/instance.h"

namespace ply_slam {

struct MaskCarrierParams {
  int samples_per_instance = 40;  // corners tracked inside each mask
  int margin_px = 4;              // extra dilation on top of the spread of the flow
  // Growth by OpenCV's elliptic kernel costs O(radius) per pixel: 0.2 ms at 8 px, 7.6 ms at 40 px
  // on a person's box (one thread), where a distance map's disc costs 0.4-0.7 ms at any radius.
  // Radii above this use the distance map (its disc differs from OpenCV's kernel by a pixel at
  // the rim); 0 = OpenCV's kernel at every radius (InstanceMemory: offline figures bit-exact).
  int largest_kernel_px = 0;
};

// Live masks are hundreds of ms old and grow by tens of pixels (LiveSegmenter): the distance
// map from 10 px, where the two cost the same.
inline MaskCarrierParams liveMaskCarrierParams() {
  MaskCarrierParams params;
  params.largest_kernel_px = 10;
  return params;
}

// Moves instance masks from the frame they were segmented in to a later frame: sparse
// Lucas-Kanade flow of corners inside each mask, the mask shifted by their median flow and
// dilated by how much the flows disagree (a person turning or the camera rotating), so the
// carried mask covers the object rather than trailing it.
class MaskCarrier {
 public:
  // Instances made ready to be carried from the frame they were segmented in: that frame's
  // pyramid and each instance's corners, found once however many frames they are carried to.
  struct Source {
    std::vector<Instance> instances;
    cv::Size size;  // of the frame
    std::vector<cv::Mat> pyramid;
    std::vector<cv::Rect> boxes;                    // each mask's bounding box
    std::vector<std::vector<cv::Point2f>> corners;  // well inside each mask
  };
  explicit MaskCarrier(const MaskCarrierParams& params = {}) : params_(params) {}

  // from_gray: 8UC1; the instances' masks of its size.
  Source prepare(const std::vector<Instance>& instances, const cv::Mat& from_gray) const;
  // to_gray: 8UC1 of the source frame's size.
  std::vector<Instance> carry(const Source& source, const cv::Mat& to_gray) const;
  std::vector<Instance> carry(const std::vector<Instance>& instances, const cv::Mat& from_gray,
                              const cv::Mat& to_gray) const {
    return carry(prepare(instances, from_gray), to_gray);
  }

 private:
  MaskCarrierParams params_;
};

}  // namespace ply_slam
