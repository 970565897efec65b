// The mapping side's intake of tracking (LandmarkCreator) on real fr1 frames, and the tracker's
// side of the contract: it writes to the map only through its LandmarkSink.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>
#include <set>

#include "ply_slam/features/orb_extractor.h"
#include "ply_slam/io/tum_sequence.h"
#include "ply_slam/mapping/landmark_creator.h"
#include "ply_slam/system/system_config.h"
#include "ply_slam/tracking/tracker.h"
#include "shared_data.h"

namespace ply_slam {
namespace {

class Fr1Frames {
 public:
  Fr1Frames()
      : config_(loadConfig(std::string(PLY_SLAM_SOURCE_DIR) + "/config/tum_fr1.yaml")),
        sequence_(folder()),
        extractor_(config_.orb) {}

  static std::string folder() { return test::sharedPath("data/tum/rgbd_dataset_freiburg1_xyz_37"); }
  const SystemConfig& config() const { return config_; }
  Frame frame(size_t i) const {
    const RgbdImages images = sequence_.load(i, config_.camera.depth_factor);
    cv::Mat gray;
    cv::cvtColor(images.rgb, gray, cv::COLOR_BGR2GRAY);
    return Frame(static_cast<long>(i), images.stamp,
                 FrameFeatures::extract(gray, images.depth, config_.camera, extractor_));
  }

 private:
  SystemConfig config_;
  TumSequence sequence_;
  OrbExtractor extractor_;
};

// A LandmarkCreator that passes on only what `forward_statistics` lets through: keyframes
// always, visible / found counts and line fits only when asked.
class FilteringSink : public LandmarkSink {
 public:
  FilteringSink(LandmarkCreator& creator, bool forward_statistics)
      : creator_(creator), forward_(forward_statistics) {}
  void countVisible(const std::vector<MapPoint*>& in_view) override {
    if (forward_) creator_.countVisible(in_view);
  }
  void recordTracked(const Frame& frame, bool fuse_lines) override {
    if (forward_) creator_.recordTracked(frame, fuse_lines);
  }
  std::shared_ptr<KeyFrame> addKeyFrame(Frame& frame) override {
    return creator_.addKeyFrame(frame);
  }

 private:
  LandmarkCreator& creator_;
  const bool forward_;
};

TEST(LandmarkCreator, KeyFrameMapsTheFeaturesWithDepthInRangeAndObservesItsMatches) {
  PLY_SLAM_REQUIRE_SHARED(Fr1Frames::folder());
  const Fr1Frames frames;
  const SystemConfig& config = frames.config();
  Map map;
  const double max_depth = 1.2;  // fr1_xyz's desk lies 0.6-2.5 m away: some in, some out
  LandmarkCreator creator(config.camera, max_depth, config.lines, map);

  Frame first = frames.frame(0);
  const FrameFeatures& f = first.features;
  size_t in_range = 0, with_depth = 0;
  for (size_t i = 0; i < f.size(); ++i) {
    with_depth += f.hasDepth(i);
    in_range += f.hasDepth(i) && f.depth[i] <= max_depth;
  }
  ASSERT_GT(in_range, 100u);
  ASSERT_GT(with_depth, in_range + 50);  // the range gate is exercised
  const auto kf = creator.addKeyFrame(first);
  EXPECT_EQ(map.mapPoints().size(), in_range);
  for (size_t i = 0; i < f.size(); ++i) {
    const auto& p = first.map_points[i];
    ASSERT_EQ(p != nullptr, f.hasDepth(i) && f.depth[i] <= max_depth) << "feature " << i;
    if (!p) continue;
    EXPECT_EQ(kf->map_points[i], p);
    ASSERT_EQ(p->observations(), 1);
    // At the identity pose the landmark is the feature's back-projection.
    EXPECT_LT((p->position - config.camera.backProject(f.undistorted[i], f.depth[i])).norm(), 1e-9);
  }

  // A second keyframe that matched some of them: they gain an observation, no new landmark is
  // made for those features, and the others with depth in range become landmarks.
  Frame second = frames.frame(1);
  second.T_cw = Eigen::Isometry3d::Identity();
  size_t linked = 0, new_ones = 0;
  for (size_t i = 0; i < second.features.size() && i < f.size(); ++i) {
    if (!first.map_points[i] || i % 2 != 0) continue;
    second.map_points[i] = first.map_points[i];
    second.outlier[i] = false;
    ++linked;
  }
  for (size_t i = 0; i < second.features.size(); ++i)
    new_ones += !second.map_points[i] && second.features.hasDepth(i) &&
                second.features.depth[i] <= max_depth;
  ASSERT_GT(linked, 20u);
  creator.addKeyFrame(second);
  EXPECT_EQ(map.mapPoints().size(), in_range + new_ones);
  size_t observed_twice = 0;
  for (const auto& p : map.mapPoints()) observed_twice += p->observations() == 2;
  EXPECT_EQ(observed_twice, linked);
}

// Tracking that writes statistics itself would leave counts behind with a sink that drops
// them; through the whole sink it leaves plenty.
TEST(Tracker, WritesToTheMapOnlyThroughItsSink) {
  PLY_SLAM_REQUIRE_SHARED(Fr1Frames::folder());
  const Fr1Frames frames;
  const SystemConfig& config = frames.config();
  const auto track = [&](bool forward_statistics) {
    Map map;
    LandmarkCreator creator(config.camera, config.tracking.max_point_depth, config.lines, map);
    FilteringSink sink(creator, forward_statistics);
    Tracker tracker(config.camera, config.tracking, config.orb, config.lines, map, sink);
    for (size_t i = 0; i < 8; ++i) {
      Frame f = frames.frame(i);
      EXPECT_EQ(tracker.track(f).state, TrackingState::kOk) << "frame " << i;
    }
    int visible = 0, found = 0;
    for (const auto& p : map.mapPoints()) {
      visible += p->visible;
      found += p->found;
    }
    return std::make_pair(visible, found);
  };
  const auto [visible_dropped, found_dropped] = track(false);
  EXPECT_EQ(visible_dropped, 0);
  EXPECT_EQ(found_dropped, 0);
  const auto [visible, found] = track(true);
  EXPECT_GT(visible, 1000);
  EXPECT_GT(found, 500);
  EXPECT_LE(found, visible);
}

// The mapping side's found / visible ratio retires points: a landmark counts in view at most once
// per frame, also when the motion model searches a second time in a wider window (jumps over
// frames the prediction does not follow).
TEST(Tracker, CountsEachLandmarkInViewOncePerFrame) {
  PLY_SLAM_REQUIRE_SHARED(Fr1Frames::folder());
  const Fr1Frames frames;
  const SystemConfig& config = frames.config();
  Map map;
  LandmarkCreator creator(config.camera, config.tracking.max_point_depth, config.lines, map);
  struct CountingSink : FilteringSink {
    using FilteringSink::FilteringSink;
    void countVisible(const std::vector<MapPoint*>& in_view) override {
      std::set<const MapPoint*> once(in_view.begin(), in_view.end());
      repeated += in_view.size() - once.size();
      counted += in_view.size();
      FilteringSink::countVisible(in_view);
    }
    size_t repeated = 0, counted = 0;
  } sink(creator, true);
  Tracker tracker(config.camera, config.tracking, config.orb, config.lines, map, sink);
  for (size_t i : {0, 1, 2, 12, 13, 24, 25, 31}) {
    Frame f = frames.frame(i);
    EXPECT_EQ(tracker.track(f).state, TrackingState::kOk) << "frame " << i;
  }
  EXPECT_GT(sink.counted, 1000u);
  EXPECT_EQ(sink.repeated, 0u);
}

}  // namespace
}  // namespace ply_slam
