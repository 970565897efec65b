#pragma once

#include <memory>
#include <optional>

#include "ply_slam/semantic/mask_carrier.h"
#include "ply_slam/semantic/segmenter.h"

namespace ply_slam {

// A reproducible model of LiveSegmenter: the network segments every `lag`-th frame and its
// result is ready `lag` frames later, as when a pass takes `lag` frame periods; each frame gets
// the newest ready result carried to it as LiveSegmenter carries it, so masks are lag ..
// 2 lag - 1 frames old (live on 2 cores with YOLO 480x640: 4-5 passes a second at 30 Hz,
// lag 6-8). Live runs depend on timing; this one repeats bit for bit, so what the masks' age
// costs can be measured and tested.
class LaggedSegmenter : public Segmenter {
 public:
  LaggedSegmenter(std::unique_ptr<Segmenter> segmenter, int lag,
                  MaskCarrierParams carrier = liveMaskCarrierParams());

  std::vector<Instance> segment(const RgbdImages& images) override;
  std::string name() const override { return segmenter_->name(); }
  std::string description() const override;

 private:
  std::unique_ptr<Segmenter> segmenter_;
  int lag_;
  MaskCarrier carrier_;
  long frame_ = 0;
  std::optional<MaskCarrier::Source> ready_;    // what frames are given
  std::optional<MaskCarrier::Source> running_;  // segmented, ready at the next multiple of lag
};

}  // namespace ply_slam
