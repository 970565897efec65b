// System::process input checks: every kind of unusable frame throws InvalidFrame with a message
// naming the fault and leaves the system as it was, so real frames around it track normally.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

#include "ply_slam/io/tum_sequence.h"
#include "ply_slam/system/system.h"
#include "ply_slam/system/system_config.h"
#include "shared_data.h"

namespace ply_slam {
namespace {

const std::string kConfig = std::string(PLY_SLAM_SOURCE_DIR) + "/config/tum_fr1.yaml";
const char* const kSequence = "data/tum/rgbd_dataset_freiburg1_xyz_37";

// Expects process(images) to throw InvalidFrame whose message contains every fragment.
void expectInvalid(System& system, const RgbdImages& images,
                   const std::vector<std::string>& fragments) {
  try {
    system.process(images);
    ADD_FAILURE() << "frame accepted, expected InvalidFrame mentioning '" << fragments.front()
                  << "'";
  } catch (const InvalidFrame& e) {
    const std::string message = e.what();
    for (const auto& fragment : fragments)
      EXPECT_NE(message.find(fragment), std::string::npos)
          << "message '" << message << "' lacks '" << fragment << "'";
  } catch (const std::exception& e) {
    ADD_FAILURE() << "threw a non-InvalidFrame: " << e.what();
  }
}

// A copy of `good` with one thing changed.
RgbdImages modified(const RgbdImages& good, const std::function<void(RgbdImages&)>& change) {
  RgbdImages images;
  images.stamp = good.stamp;
  images.depth_stamp = good.depth_stamp;
  images.rgb = good.rgb.clone();
  images.depth = good.depth.clone();
  change(images);
  return images;
}

// What a bad frame must not touch.
struct Snapshot {
  size_t trajectory = 0, keyframes = 0;
  explicit Snapshot(const System& s)
      : trajectory(s.cameraTrajectory().size()), keyframes(s.map().keyFrames().size()) {}
  bool operator==(const Snapshot& o) const {
    return trajectory == o.trajectory && keyframes == o.keyframes;
  }
};

class SystemInputTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const std::string folder = test::sharedPath(kSequence);
    PLY_SLAM_REQUIRE_SHARED(folder);
    config_ = loadConfig(kConfig);
    const TumSequence sequence(folder);
    ASSERT_GE(sequence.size(), 2u);
    frames_[0] = sequence.load(0, config_.camera.depth_factor);
    frames_[1] = sequence.load(1, config_.camera.depth_factor);
  }

  // Every image fault, each at a stamp after the good frames' so only the images are wrong.
  std::vector<std::pair<RgbdImages, std::vector<std::string>>> badImages(const RgbdImages& good,
                                                                         double stamp) const {
    std::vector<std::pair<RgbdImages, std::vector<std::string>>> bad;
    auto add = [&](std::function<void(RgbdImages&)> change, std::vector<std::string> fragments) {
      RgbdImages images = modified(good, change);
      images.stamp = stamp;
      bad.emplace_back(images, fragments);
    };
    add([](RgbdImages& f) { f.rgb.release(); }, {"empty", "RGB"});
    add([](RgbdImages& f) { f.depth.release(); }, {"empty", "depth"});
    add([](RgbdImages& f) { cv::cvtColor(f.rgb.clone(), f.rgb, cv::COLOR_BGR2GRAY); },
        {"RGB", "CV_8UC1"});
    add([](RgbdImages& f) { f.depth.convertTo(f.depth, CV_16UC1, 5000.0); },
        {"depth", "32FC1", "CV_16UC1"});
    add([](RgbdImages& f) { f.rgb = f.rgb(cv::Rect(0, 0, 320, 240)).clone(); }, {"size"});
    add(
        [](RgbdImages& f) {
          f.rgb = f.rgb(cv::Rect(0, 0, 320, 240)).clone();
          f.depth = f.depth(cv::Rect(0, 0, 320, 240)).clone();
        },
        {"320x240", "640x480"});
    return bad;
  }

  SystemConfig config_;
  RgbdImages frames_[2];
};

TEST_F(SystemInputTest, BadFramesThrowAndLeaveTheSystemTracking) {
  System system(config_);
  const FrameResult first = system.process(frames_[0]);
  ASSERT_EQ(first.tracking.state, TrackingState::kOk) << "the first frame initialises";
  const Snapshot after_first(system);
  ASSERT_EQ(after_first.trajectory, 1u);

  // Image faults, stamped after the next good frame: a rejected frame must not move the clock.
  for (const auto& [images, fragments] : badImages(frames_[1], frames_[1].stamp + 0.5)) {
    SCOPED_TRACE(fragments.front());
    expectInvalid(system, images, fragments);
    EXPECT_TRUE(Snapshot(system) == after_first);
  }
  // Stamp faults with good images.
  expectInvalid(system, modified(frames_[1], [&](RgbdImages& f) { f.stamp = frames_[0].stamp; }),
                {"stamp"});
  expectInvalid(system,
                modified(frames_[1], [&](RgbdImages& f) { f.stamp = frames_[0].stamp - 1.0; }),
                {"stamp"});
  EXPECT_TRUE(Snapshot(system) == after_first);

  const FrameResult second = system.process(frames_[1]);
  EXPECT_EQ(second.tracking.state, TrackingState::kOk);
  EXPECT_EQ(second.frame_id, first.frame_id + 1) << "rejected frames must not take frame ids";
  EXPECT_GE(second.tracking.inliers, config_.tracking.min_tracked_points);
  const Trajectory& trajectory = system.cameraTrajectory();
  ASSERT_EQ(trajectory.size(), 2u);
  EXPECT_EQ(trajectory[0].stamp, frames_[0].stamp);
  EXPECT_EQ(trajectory[1].stamp, frames_[1].stamp);
  // fr1_xyz moves a few mm between consecutive frames: a tracked, not a wild, pose.
  const double step = (trajectory[1].T_wc.translation() - trajectory[0].T_wc.translation()).norm();
  EXPECT_LT(step, 0.05);

  // The same two frames without the bad ones in between give the same pose: nothing of the
  // rejected frames stayed in the system.
  System clean(config_);
  clean.process(frames_[0]);
  clean.process(frames_[1]);
  ASSERT_EQ(clean.cameraTrajectory().size(), 2u);
  EXPECT_LT((clean.cameraTrajectory()[1].T_wc.matrix() - trajectory[1].T_wc.matrix())
                .cwiseAbs()
                .maxCoeff(),
            1e-12);
  EXPECT_EQ(clean.map().keyFrames().size(), system.map().keyFrames().size());
}

TEST_F(SystemInputTest, BadFramesBeforeTheFirstFrameChangeNothing) {
  System system(config_);
  for (const auto& [images, fragments] : badImages(frames_[0], frames_[0].stamp)) {
    SCOPED_TRACE(fragments.front());
    expectInvalid(system, images, fragments);
  }
  EXPECT_TRUE(system.cameraTrajectory().empty());
  EXPECT_TRUE(system.map().keyFrames().empty());
  const FrameResult first = system.process(frames_[0]);
  EXPECT_EQ(first.frame_id, 0);
  EXPECT_EQ(first.tracking.state, TrackingState::kOk);
}

TEST_F(SystemInputTest, NonFiniteStampsAreRejected) {
  const auto with_stamp = [&](double stamp) {
    return modified(frames_[1], [stamp](RgbdImages& f) { f.stamp = stamp; });
  };
  // NaN compares false with everything: accepted, it switches the ordering check off for good.
  {
    System system(config_);
    ASSERT_EQ(system.process(frames_[0]).tracking.state, TrackingState::kOk);
    expectInvalid(system, with_stamp(std::numeric_limits<double>::quiet_NaN()), {"stamp"});
    expectInvalid(system, with_stamp(1.0), {"stamp"});
  }
  // +inf accepted would refuse every later frame.
  {
    System system(config_);
    ASSERT_EQ(system.process(frames_[0]).tracking.state, TrackingState::kOk);
    expectInvalid(system, with_stamp(std::numeric_limits<double>::infinity()), {"stamp"});
    EXPECT_NO_THROW(system.process(frames_[1]));
    EXPECT_EQ(system.cameraTrajectory().size(), 2u);
  }
}

TEST_F(SystemInputTest, AllZeroDepthDoesNotInitialise) {
  System system(config_);
  const RgbdImages no_depth = modified(frames_[0], [](RgbdImages& f) {
    f.depth.setTo(0.f);
    f.stamp -= 1.0;
  });
  FrameResult r;
  ASSERT_NO_THROW(r = system.process(no_depth));
  EXPECT_EQ(r.tracking.state, TrackingState::kNotInitialised);
  EXPECT_TRUE(system.cameraTrajectory().empty());
  EXPECT_TRUE(system.map().keyFrames().empty());

  // NaN depth is invalid depth too (System::process contract).
  const RgbdImages nan_depth = modified(frames_[0], [](RgbdImages& f) {
    f.depth.setTo(std::numeric_limits<float>::quiet_NaN());
    f.stamp -= 0.5;
  });
  ASSERT_NO_THROW(r = system.process(nan_depth));
  EXPECT_EQ(r.tracking.state, TrackingState::kNotInitialised);
  EXPECT_TRUE(system.map().keyFrames().empty());

  // Real depth afterwards initialises and tracks.
  EXPECT_EQ(system.process(frames_[0]).tracking.state, TrackingState::kOk);
  EXPECT_EQ(system.process(frames_[1]).tracking.state, TrackingState::kOk);
  EXPECT_EQ(system.cameraTrajectory().size(), 2u);
}

}  // namespace
}  // namespace ply_slam
