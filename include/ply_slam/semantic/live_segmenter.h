#pragma once

#include <condition_variable>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "ply_slam/semantic/mask_carrier.h"
#include "ply_slam/semantic/segmenter.h"

namespace ply_slam {

// Live-mode segmentation (DESIGN.md, data flow step 1): a worker thread runs the network on
// the newest frame it was given and keeps the newest finished result. Tracking never waits:
// each frame takes that result, carried to itself by MaskCarrier (the masks are a few frames
// old while the network runs).
class LiveSegmenter {
 public:
  explicit LiveSegmenter(std::unique_ptr<Segmenter> segmenter, MaskCarrierParams carrier = {});
  ~LiveSegmenter();
  LiveSegmenter(const LiveSegmenter&) = delete;
  LiveSegmenter& operator=(const LiveSegmenter&) = delete;

  // Hands the frame to the worker, replacing one still waiting. Returns at once.
  void submit(const RgbdImages& images);
  // The newest finished segmentation carried to `current`; empty before the first one.
  std::vector<Instance> instancesFor(const RgbdImages& current);

  // Seconds from the segmented frame to the frame it was used for, over instancesFor calls.
  double meanAgeSeconds() const;
  long segmentedFrames() const;
  // The worker's last error (a frame the segmenter rejected), "" when none.
  std::string lastError() const;

 private:
  void run();

  struct Result {
    double stamp = 0.0;
    cv::Mat gray;
    std::vector<Instance> instances;
  };

  std::unique_ptr<Segmenter> segmenter_;
  MaskCarrier carrier_;
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  std::optional<RgbdImages> pending_;
  std::shared_ptr<const Result> latest_;
  bool stop_ = false;
  long segmented_ = 0;
  double age_sum_ = 0.0;
  long age_count_ = 0;
  std::string last_error_;
  std::thread worker_;  // last: starts after everything it uses exists
};

}  // namespace ply_slam
