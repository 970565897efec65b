#include "ply_slam/semantic/lagged_segmenter.h"

#include <opencv2/imgproc.hpp>
#include <stdexcept>

namespace ply_slam {

LaggedSegmenter::LaggedSegmenter(std::unique_ptr<Segmenter> segmenter, int lag,
                                 MaskCarrierParams carrier)
    : segmenter_(std::move(segmenter)), lag_(lag), carrier_(carrier) {
  if (!segmenter_) throw std::invalid_argument("LaggedSegmenter needs a segmenter");
  if (lag_ < 1) throw std::invalid_argument("LaggedSegmenter: lag must be >= 1 frame");
}

std::vector<Instance> LaggedSegmenter::segment(const RgbdImages& images) {
  cv::Mat gray;
  cv::cvtColor(images.rgb, gray, cv::COLOR_BGR2GRAY);
  if (frame_++ % lag_ == 0) {  // the pass that started lag frames ago is done; start the next
    if (running_) ready_ = std::move(running_);
    running_ = carrier_.prepare(segmenter_->segment(images), gray);
  }
  if (!ready_ || ready_->size != gray.size()) return {};
  return carrier_.carry(*ready_, gray);
}

std::string LaggedSegmenter::description() const {
  return segmenter_->description() + ", every " + std::to_string(lag_) + "-th frame, ready " +
         std::to_string(lag_) + " frames later and carried";
}

}  // namespace ply_slam
