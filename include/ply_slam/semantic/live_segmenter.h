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
// old while the network runs). The worker runs below tracking's priority (kBackgroundNice):
// it takes the CPU that tracking and the mapping side leave, never the other way round.
class LiveSegmenter {
 public:
  // opencv_threads > 0: cv::setNumThreads(opencv_threads) for the whole process (the network's
  // forward pass is OpenCV's only long parallel loop); 0 leaves OpenCV's default, every core.
  explicit LiveSegmenter(std::unique_ptr<Segmenter> segmenter, int opencv_threads = 0,
                         MaskCarrierParams carrier = liveMaskCarrierParams());
  ~LiveSegmenter();
  LiveSegmenter(const LiveSegmenter&) = delete;
  LiveSegmenter& operator=(const LiveSegmenter&) = delete;

  // Hands the frame to the worker, replacing one still waiting. Returns at once.
  void submit(const RgbdImages& images);
  // The newest finished segmentation carried to `current`; empty before the first one.
  std::vector<Instance> instancesFor(const RgbdImages& current);

  // The segmenter's description, with the threads and priority it runs with.
  std::string description() const;
  // Seconds from the segmented frame to the frame it was used for, over instancesFor calls.
  double meanAgeSeconds() const;
  long segmentedFrames() const;
  // Mean wall milliseconds of a forward pass with its decoding and the masks made ready to be
  // carried, over the frames segmented.
  double meanSegmentMs() const;
  // The worker's last error (a frame the segmenter rejected), "" when none.
  std::string lastError() const;

 private:
  void run();

  struct Result {
    double stamp = 0.0;
    MaskCarrier::Source source;  // the instances, ready to be carried (made on the worker)
  };

  std::unique_ptr<Segmenter> segmenter_;
  MaskCarrier carrier_;
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  std::optional<RgbdImages> pending_;
  std::shared_ptr<const Result> latest_;
  bool stop_ = false;
  long segmented_ = 0;
  double segment_ms_sum_ = 0.0;
  double age_sum_ = 0.0;
  long age_count_ = 0;
  std::string last_error_;
  std::thread worker_;  // last: starts after everything it uses exists
};

}  // namespace ply_slam
