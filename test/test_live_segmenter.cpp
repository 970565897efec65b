// Live-mode segmentation: masks carried to later frames, the worker never holding up the
// caller and always segmenting the newest frame.
#include <gtest/gtest.h>

#include <chrono>
#include <opencv2/imgproc.hpp>
#include <set>
#include <thread>

#include "ply_slam/semantic/instance_memory.h"
#include "ply_slam/semantic/lagged_segmenter.h"
#include "ply_slam/semantic/live_segmenter.h"
#include "ply_slam/semantic/mask_carrier.h"

using namespace ply_slam;

namespace {

// Noise at several scales, like a natural image: structure for every pyramid level.
cv::Mat texture(int seed) {
  cv::RNG rng(seed);
  cv::Mat sum = cv::Mat::zeros(480, 640, CV_32FC1);
  for (double sigma : {1.5, 4.0, 10.0}) {
    cv::Mat noise(480, 640, CV_32FC1);
    rng.fill(noise, cv::RNG::UNIFORM, 0.0, 1.0);
    cv::GaussianBlur(noise, noise, cv::Size(0, 0), sigma);
    cv::normalize(noise, noise, 0, 1, cv::NORM_MINMAX);
    sum += noise;
  }
  cv::Mat image;
  cv::normalize(sum, sum, 0, 255, cv::NORM_MINMAX);
  sum.convertTo(image, CV_8UC1);
  return image;
}

cv::Mat shifted(const cv::Mat& image, double dx, double dy) {
  cv::Mat out;
  cv::warpAffine(image, out, cv::Matx23d(1, 0, dx, 0, 1, dy), image.size(), cv::INTER_LINEAR,
                 cv::BORDER_REFLECT);
  return out;
}

double share(const cv::Mat& covered, const cv::Mat& by) {
  return static_cast<double>(cv::countNonZero(covered & by)) / cv::countNonZero(covered);
}

// An object (its own texture) moving over a background that moves differently.
struct MovingObject {
  cv::Mat from, to, mask_from, mask_to;
};

MovingObject movingObject(double obj_dx, double obj_dy, double bg_dx) {
  const cv::Mat background = texture(1), object = texture(2);
  MovingObject m;
  m.mask_from = cv::Mat::zeros(480, 640, CV_8UC1);
  cv::ellipse(m.mask_from, {300, 240}, {60, 120}, 0, 0, 360, 255, cv::FILLED);
  m.mask_to = shifted(m.mask_from, obj_dx, obj_dy) > 127;
  m.from = background.clone();
  object.copyTo(m.from, m.mask_from);
  m.to = shifted(background, bg_dx, 0);
  shifted(object, obj_dx, obj_dy).copyTo(m.to, m.mask_to);
  return m;
}

class SlowSegmenter : public Segmenter {
 public:
  std::vector<Instance> segment(const RgbdImages& images) override {
    std::this_thread::sleep_for(std::chrono::milliseconds(60));
    if (images.stamp < 0) throw std::runtime_error("negative stamp");
    cv::Mat mask = cv::Mat::zeros(images.rgb.size(), CV_8UC1);
    cv::rectangle(mask, cv::Rect(100, 100, 50, 80), 255, cv::FILLED);
    return {{1, "person", 0.9f, mask}};
  }
  std::string name() const override { return "slow"; }
};

RgbdImages frame(double stamp) {
  RgbdImages images;
  images.stamp = stamp;
  cv::cvtColor(texture(3), images.rgb, cv::COLOR_GRAY2BGR);
  images.depth = cv::Mat(480, 640, CV_32FC1, cv::Scalar(1.0f));
  return images;
}

bool waitFor(const LiveSegmenter& live, long frames) {
  for (int i = 0; i < 500 && live.segmentedFrames() < frames; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  return live.segmentedFrames() >= frames;
}

}  // namespace

TEST(MaskCarrier, FollowsAnObjectThatMovesAgainstTheBackground) {
  const MovingObject m = movingObject(18, -9, -6);
  const Instance instance{1, "person", 1.0f, m.mask_from};
  const auto carried = MaskCarrier().carry({instance}, m.from, m.to);
  ASSERT_EQ(carried.size(), 1u);
  EXPECT_EQ(carried[0].class_name, "person");
  // The carried mask covers the object where it is now, and not much more.
  EXPECT_GT(share(m.mask_to, carried[0].mask), 0.98);
  EXPECT_LT(cv::countNonZero(carried[0].mask), 1.25 * cv::countNonZero(m.mask_to));
  // The stale mask would not have.
  EXPECT_LT(share(m.mask_to, m.mask_from), 0.85);
}

TEST(MaskCarrier, RejectsImagesOfDifferentSizes) {
  const cv::Mat small(240, 320, CV_8UC1, cv::Scalar(0));
  EXPECT_THROW(MaskCarrier().carry({}, texture(1), small), std::invalid_argument);
}

// Masks carried live are hundreds of ms old and grow by tens of pixels: past 10 px
// (liveMaskCarrierParams) the growth is the disc of a distance map. Without texture nothing is
// followed, so the mask stays where it was, grown by the margin alone.
TEST(MaskCarrier, GrowsAStaleMaskByAWideDiscWhereNothingIsFollowed) {
  const cv::Mat blank(480, 640, CV_8UC1, cv::Scalar(128));
  cv::Mat mask = cv::Mat::zeros(480, 640, CV_8UC1);
  mask(cv::Rect(300, 200, 40, 80)).setTo(255);
  MaskCarrierParams params = liveMaskCarrierParams();
  params.margin_px = 30;
  const auto carried = MaskCarrier(params).carry({{1, "person", 1.0f, mask}}, blank, blank);
  ASSERT_EQ(carried.size(), 1u);
  const cv::Mat& grown = carried[0].mask;
  EXPECT_EQ(grown.at<uchar>(240, 339 + 30), 255);  // 30 px right of the box
  EXPECT_EQ(grown.at<uchar>(240, 339 + 31), 0);
  EXPECT_EQ(grown.at<uchar>(200 - 30, 320), 255);  // 30 px above
  EXPECT_EQ(grown.at<uchar>(200 - 31, 320), 0);
  EXPECT_EQ(grown.at<uchar>(200 - 21, 300 - 21), 255);  // the corner: 29.7 px away
  EXPECT_EQ(grown.at<uchar>(200 - 22, 300 - 22), 0);    // 31.1 px: a disc, not a square
}

TEST(InstanceMemory, CarriesAMissedPersonOnForAFewFrames) {
  const MovingObject m = movingObject(10, 4, -3);
  const Instance person{7, "person", 0.9f, m.mask_from};
  InstanceMemory memory(2);
  auto judged = memory.complete({person}, m.from);
  ASSERT_EQ(judged.size(), 1u);
  EXPECT_TRUE(memory.presumed().empty());
  memory.remember(judged, {7}, {7}, m.from);
  // Seen again: nothing is added.
  EXPECT_EQ(memory.complete({{3, "person", 0.8f, m.mask_to}}, m.to).size(), 1u);
  // Missed: the remembered mask comes along, moved with the object, as a new instance; one
  // measurement is not enough to presume it moving.
  judged = memory.complete({}, m.to);
  ASSERT_EQ(judged.size(), 1u);
  EXPECT_EQ(judged[0].class_name, "person");
  EXPECT_NE(judged[0].id, 7);
  EXPECT_TRUE(memory.presumed().empty());
  EXPECT_GT(share(m.mask_to, judged[0].mask), 0.98);
  // Carried for at most 2 frames, even while it is measured moving.
  memory.remember(judged, {judged[0].id}, {judged[0].id}, m.to);
  judged = memory.complete({}, m.to);
  ASSERT_EQ(judged.size(), 1u);
  EXPECT_EQ(memory.presumed(), std::set<int>{judged[0].id});  // measured twice in a row
  memory.remember(judged, {judged[0].id}, {judged[0].id}, m.to);
  EXPECT_TRUE(memory.complete({}, m.to).empty());
  memory.remember({person}, {}, {}, m.from);  // a person judged static is not remembered
  EXPECT_TRUE(memory.complete({}, m.to).empty());
}

TEST(InstanceMemory, PresumesAPersonMeasuredMovingDynamicForAFewFrames) {
  const MovingObject m = movingObject(10, 4, -3);
  const auto frame = [&](int k) { return k % 2 ? m.to : m.from; };
  const auto mask = [&](int k) { return k % 2 ? m.mask_to : m.mask_from; };
  InstanceMemory memory(2);
  // Measured moving once: not presumed in the next frame.
  auto judged = memory.complete({{10, "person", 0.9f, mask(0)}}, frame(0));
  memory.remember(judged, {10}, {10}, frame(0));
  judged = memory.complete({{11, "person", 0.9f, mask(1)}}, frame(1));
  EXPECT_TRUE(memory.presumed().empty());
  // Twice in a row: presumed for the next 2 frames although they show it still.
  memory.remember(judged, {11}, {11}, frame(1));
  for (int k = 2; k <= 3; ++k) {
    judged = memory.complete({{10 + k, "person", 0.9f, mask(k)}}, frame(k));
    ASSERT_EQ(judged.size(), 1u);
    EXPECT_EQ(memory.presumed(), std::set<int>{10 + k}) << "frame " << k;
    memory.remember(judged, {}, memory.presumed(), frame(k));
  }
  // A person who stopped is judged on their own evidence again.
  judged = memory.complete({{14, "person", 0.9f, mask(4)}}, frame(4));
  EXPECT_TRUE(memory.presumed().empty());
  // Another class where the person was is not taken for it; the person is carried on.
  memory.remember(judged, {14}, {14}, frame(4));
  judged = memory.complete({{15, "person", 0.9f, mask(5)}}, frame(5));
  memory.remember(judged, {15}, {15}, frame(5));
  judged = memory.complete({{16, "chair", 0.9f, mask(6)}}, frame(6));
  ASSERT_EQ(judged.size(), 2u);
  EXPECT_EQ(memory.presumed(), std::set<int>{judged[1].id});
}

TEST(InstanceMemory, APresumptionIsNotAMeasurement) {
  const MovingObject m = movingObject(10, 4, -3);
  InstanceMemory memory(3);
  // Dynamic for want of matched features, then measured moving once: no run of two yet.
  auto judged = memory.complete({{10, "person", 0.9f, m.mask_from}}, m.from);
  memory.remember(judged, {}, {10}, m.from);
  judged = memory.complete({{11, "person", 0.9f, m.mask_to}}, m.to);
  EXPECT_TRUE(memory.presumed().empty());
  memory.remember(judged, {11}, {11}, m.to);
  memory.complete({{12, "person", 0.9f, m.mask_from}}, m.from);
  EXPECT_TRUE(memory.presumed().empty());
}

TEST(LiveSegmenter, NothingBeforeTheFirstResultThenTheNewestFrame) {
  LiveSegmenter live(std::make_unique<SlowSegmenter>());
  EXPECT_TRUE(live.instancesFor(frame(0.0)).empty());
  // Frames arrive faster than the segmenter runs: it skips to the newest.
  for (int i = 1; i <= 6; ++i) {
    live.submit(frame(i * 0.033));
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  ASSERT_TRUE(waitFor(live, 1));
  std::this_thread::sleep_for(std::chrono::milliseconds(200));  // let it reach the last one
  EXPECT_LT(live.segmentedFrames(), 6);
  const auto instances = live.instancesFor(frame(6 * 0.033));
  ASSERT_EQ(instances.size(), 1u);
  // Same stamp as the segmented frame: the mask comes unchanged (not carried, not dilated).
  EXPECT_EQ(cv::countNonZero(instances[0].mask), 50 * 80);
  EXPECT_NEAR(live.meanAgeSeconds(), 0.0, 1e-9);
  // A later frame gets the mask carried, and the age is counted.
  EXPECT_EQ(live.instancesFor(frame(7 * 0.033)).size(), 1u);
  EXPECT_NEAR(live.meanAgeSeconds(), 0.033 / 2, 1e-6);
}

TEST(LiveSegmenter, AFrameTheSegmenterRejectsKeepsThePreviousResult) {
  LiveSegmenter live(std::make_unique<SlowSegmenter>());
  live.submit(frame(1.0));
  ASSERT_TRUE(waitFor(live, 1));
  live.submit(frame(-1.0));
  for (int i = 0; i < 200 && live.lastError().empty(); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  EXPECT_EQ(live.lastError(), "negative stamp");
  EXPECT_EQ(live.segmentedFrames(), 1);
  EXPECT_EQ(live.instancesFor(frame(1.0)).size(), 1u);
}

namespace {

// An ellipse of its own texture moving 4 px right per frame over a still background; its
// segmenter records which frames it was asked for and returns the object's true mask there.
struct MovingScene {
  cv::Mat background = texture(1), object = texture(2), mask0;
  MovingScene() {
    mask0 = cv::Mat::zeros(480, 640, CV_8UC1);
    cv::ellipse(mask0, {200, 240}, {60, 120}, 0, 0, 360, 255, cv::FILLED);
  }
  cv::Mat maskAt(int k) const { return shifted(mask0, 4.0 * k, 0) > 127; }
  RgbdImages frameAt(int k) const {
    cv::Mat gray = background.clone();
    shifted(object, 4.0 * k, 0).copyTo(gray, maskAt(k));
    RgbdImages images;
    images.stamp = k / 30.0;
    cv::cvtColor(gray, images.rgb, cv::COLOR_GRAY2BGR);
    images.depth = cv::Mat(480, 640, CV_32FC1, cv::Scalar(1.0f));
    return images;
  }
};

class RecordingSegmenter : public Segmenter {
 public:
  RecordingSegmenter(const MovingScene& scene, std::vector<int>& asked)
      : scene_(scene), asked_(asked) {}
  std::vector<Instance> segment(const RgbdImages& images) override {
    const int k = cvRound(images.stamp * 30.0);
    asked_.push_back(k);
    return {{k, "person", 0.9f, scene_.maskAt(k)}};
  }
  std::string name() const override { return "recording"; }

 private:
  const MovingScene& scene_;
  std::vector<int>& asked_;
};

}  // namespace

TEST(LaggedSegmenter, SegmentsEveryLagthFrameAndGivesItLagFramesLaterCarried) {
  const MovingScene scene;
  std::vector<int> asked;
  constexpr int kLag = 4;
  LaggedSegmenter lagged(std::make_unique<RecordingSegmenter>(scene, asked), kLag);
  for (int k = 0; k < 14; ++k) {
    const std::vector<Instance> instances = lagged.segment(scene.frameAt(k));
    if (k < kLag) {  // the first pass is still running
      EXPECT_TRUE(instances.empty()) << "frame " << k;
      continue;
    }
    ASSERT_EQ(instances.size(), 1u) << "frame " << k;
    // The newest pass that is done: started at the last multiple of lag before this one.
    EXPECT_EQ(instances[0].id, (k / kLag - 1) * kLag) << "frame " << k;
    // Carried onto the object where it is now (it moved 16-28 px since), not left behind.
    EXPECT_GT(share(scene.maskAt(k), instances[0].mask), 0.97) << "frame " << k;
    EXPECT_LT(share(scene.maskAt(instances[0].id), scene.maskAt(k)), 0.9) << "frame " << k;
  }
  EXPECT_EQ(asked, (std::vector<int>{0, 4, 8, 12}));
}

TEST(LaggedSegmenter, RefusesALagBelowOneFrame) {
  const MovingScene scene;
  std::vector<int> asked;
  EXPECT_THROW(LaggedSegmenter(std::make_unique<RecordingSegmenter>(scene, asked), 0),
               std::invalid_argument);
}
