#include "ply_slam/semantic/live_segmenter.h"

#include <opencv2/core/utility.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

#include "ply_slam/common/stopwatch.h"
#include "ply_slam/common/thread_priority.h"

namespace ply_slam {
namespace {

cv::Mat toGray(const cv::Mat& bgr) {
  cv::Mat gray;
  cv::cvtColor(bgr, gray, cv::COLOR_BGR2GRAY);
  return gray;
}

}  // namespace

LiveSegmenter::LiveSegmenter(std::unique_ptr<Segmenter> segmenter, int opencv_threads,
                             MaskCarrierParams carrier)
    : segmenter_(std::move(segmenter)), carrier_(carrier) {
  if (!segmenter_) throw std::invalid_argument("LiveSegmenter needs a segmenter");
  if (opencv_threads > 0) cv::setNumThreads(opencv_threads);
  worker_ = std::thread([this] {
    setThisThreadsNice(kBackgroundNice);
    run();
  });
}

LiveSegmenter::~LiveSegmenter() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  worker_.join();
}

void LiveSegmenter::submit(const RgbdImages& images) {
  if (images.rgb.empty() || images.rgb.type() != CV_8UC3) return;  // System reports bad frames
  RgbdImages copy = images;
  copy.rgb = images.rgb.clone();  // the caller may reuse its buffers
  copy.depth = images.depth.clone();
  {
    std::lock_guard<std::mutex> lock(mutex_);
    pending_ = std::move(copy);
  }
  wake_.notify_one();
}

void LiveSegmenter::run() {
  for (;;) {
    RgbdImages images;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      wake_.wait(lock, [this] { return stop_ || pending_; });
      if (stop_) return;
      images = std::move(*pending_);
      pending_.reset();
    }
    auto result = std::make_shared<Result>();
    result->stamp = images.stamp;
    std::string error;
    const Stopwatch watch;
    try {
      result->source = carrier_.prepare(segmenter_->segment(images), toGray(images.rgb));
    } catch (const std::exception& e) {
      error = e.what();
    }
    std::lock_guard<std::mutex> lock(mutex_);
    if (!error.empty()) {
      last_error_ = error;
      continue;  // keep the previous result
    }
    latest_ = std::move(result);
    ++segmented_;
    segment_ms_sum_ += watch.elapsedMs();
  }
}

std::vector<Instance> LiveSegmenter::instancesFor(const RgbdImages& current) {
  std::shared_ptr<const Result> latest;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    latest = latest_;
  }
  if (!latest || current.rgb.empty() || current.rgb.size() != latest->source.size) return {};
  std::vector<Instance> instances = current.stamp == latest->stamp
                                        ? latest->source.instances
                                        : carrier_.carry(latest->source, toGray(current.rgb));
  std::lock_guard<std::mutex> lock(mutex_);
  age_sum_ += current.stamp - latest->stamp;
  ++age_count_;
  return instances;
}

double LiveSegmenter::meanAgeSeconds() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return age_count_ > 0 ? age_sum_ / age_count_ : 0.0;
}

long LiveSegmenter::segmentedFrames() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return segmented_;
}

std::string LiveSegmenter::description() const {
  return segmenter_->description() + ", live on a worker thread at nice +" +
         std::to_string(kBackgroundNice) + ", OpenCV threads " +
         std::to_string(cv::getNumThreads());
}

double LiveSegmenter::meanSegmentMs() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return segmented_ > 0 ? segment_ms_sum_ / segmented_ : 0.0;
}

std::string LiveSegmenter::lastError() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return last_error_;
}

}  // namespace ply_slam
