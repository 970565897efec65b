#pragma once

// A tracker and a mapper in one map, as System runs them in line, and a copy of the map that
// follows them by the tracker's reports and the mapping side's updates alone, as the other
// process of a two-process split would; compared field for field as it goes.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>
#include <optional>
#include <set>
#include <string>
#include <utility>

#include "map_equality.h"
#include "ply_slam/features/line_extractor.h"
#include "ply_slam/features/line_fitter.h"
#include "ply_slam/features/orb_extractor.h"
#include "ply_slam/io/tum_sequence.h"
#include "ply_slam/mapping/mapper.h"
#include "ply_slam/system/key_frame_packet_builder.h"
#include "ply_slam/system/mapping_job.h"
#include "ply_slam/system/system_config.h"
#include "ply_slam/tracking/tracker.h"

namespace ply_slam {
namespace test {

// Tracks and maps frames as System does in line, and keeps a copy of the map that follows by
// the tracker's reports and the mapping side's updates alone (as the other process of a split
// would), compared with the map every `check_every` keyframes and after each loop closure.
class ReplicaRun {
 public:
  // What goes between the two sides; by default nothing happens on the way. The job holds the
  // tracker's report and its new keyframe as the mapping side first gets it.
  struct Wire {
    virtual ~Wire() = default;
    virtual MappingJob toMapper(MappingJob job) { return job; }
    virtual MapUpdate toTracker(MapUpdate update) { return update; }
  };

  ReplicaRun(const SystemConfig& config, int check_every, Wire* wire = nullptr)
      : wire_(wire ? wire : &direct_),
        config_(config),
        check_every_(check_every),
        extractor_(config.orb),
        line_extractor_(config.lines),
        line_fitter_(config.lines, config.camera),
        mapper_(config.camera, mapperOptions(config), map_),
        creator_(config.camera, config.tracking.max_point_depth, config.lines, map_),
        tracker_(config.camera, config.tracking, config.orb, config.lines, map_, creator_) {
    creator_.reportTo(&report_);
    mapper_.setCorrectionListener(
        [this](const Eigen::Isometry3d& correction) { tracker_.applyCorrection(correction); });
  }

  void process(long i, const RgbdImages& images) {
    cv::Mat gray;
    cv::cvtColor(images.rgb, gray, cv::COLOR_BGR2GRAY);
    Frame frame(i, images.stamp,
                FrameFeatures::extract(gray, images.depth, config_.camera, extractor_));
    frame.setLines(
        FrameLines::extract(gray, images.depth, config_.camera, line_extractor_, line_fitter_));
    const TrackingResult result = tracker_.track(frame);
    ASSERT_EQ(result.state, TrackingState::kOk) << "frame " << i;
    if (!result.new_keyframe) return;
    ++keyframes;
    const std::string when = "keyframe of frame " + std::to_string(i);
    followTracker(*result.new_keyframe, when);
    if (::testing::Test::HasFatalFailure()) return;
    const bool loop = followMapper(result.new_keyframe, images, when);
    if (::testing::Test::HasFatalFailure()) return;
    if (loop || keyframes % check_every_ == 0) test::expectSameMap(follower_, map_, when);
  }

  int keyframes = 0, line_fits = 0, fused_depths = 0, changes = 0, culled_keyframes = 0;
  int loops = 0;

 private:
  void followTracker(const KeyFrame& keyframe, const std::string& when) {
    line_fits += static_cast<int>(report_.line_fits.size());
    for (const auto& link : report_.point_links) fused_depths += link.weight > 0.0;
    MappingJob job;
    job.keyframe = keyframe.unlinkedCopy();
    job.report = std::exchange(report_, TrackerReport{});
    job = wire_->toMapper(std::move(job));
    LandmarkCreator(config_.camera, config_.tracking.max_point_depth, config_.lines, follower_)
        .replay(job.report, job.keyframe);
  }

  // Maps the keyframe as System::mapKeyFrame does; true when it closed a loop.
  bool followMapper(const std::shared_ptr<KeyFrame>& keyframe, const RgbdImages& images,
                    const std::string& when) {
    MapJournal journal;
    map_.journalTo(&journal);
    const KeyFrameInsertionStats stats = mapper_.insertKeyFrame(
        keyframe, [&] { return std::set<long>{tracker_.referenceKeyFrame()->id}; });
    std::optional<LoopCorrection> loop;
    if (mapper_.recognisesPlaces())
      loop =
          mapper_.closeLoop(*keyframe, makeKeyFramePacket(*keyframe, config_.camera, images, {}));
    map_.journalTo(nullptr);
    // The whole map after a loop or a global BA written back.
    MapUpdate update = loop || stats.global_ba_applied ? mapper_.wholeMap() : stats.adjusted;
    update.journal = std::move(journal);
    changes += static_cast<int>(update.journal.entries.size());
    culled_keyframes += static_cast<int>(stats.culled_keyframes.size());
    loops += loop.has_value();
    follower_.apply(wire_->toTracker(std::move(update)));
    return loop.has_value();
  }

  Wire direct_;
  Wire* const wire_;
  const SystemConfig config_;
  const int check_every_;
  const OrbExtractor extractor_;
  const LineExtractor line_extractor_;
  const LineFitter line_fitter_;
  Map map_;
  Mapper mapper_;
  LandmarkCreator creator_;
  Tracker tracker_;
  TrackerReport report_;
  Map follower_;  // from the reports and updates only
};

}  // namespace test
}  // namespace ply_slam
