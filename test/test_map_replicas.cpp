// Two copies of the map that follow each other, as the tracker's and the mapping side's would in
// two processes: the tracker's report (TrackerReport: what it did between two keyframes, by id)
// replayed on a copy as the mapping side left it gives the tracker's map exactly, and the
// mapping side's update (MapUpdate: its journal of links, merges and erasures, and the values it
// left) applied to a copy as the tracker left it gives the mapping side's. Real fr1_rpy frames
// with lines, tracked and mapped as System does in line (fusion, local BA, culling).
#include <gtest/gtest.h>

#include <iostream>
#include <opencv2/imgproc.hpp>

#include "map_copy.h"
#include "ply_slam/common/config.h"
#include "ply_slam/features/line_extractor.h"
#include "ply_slam/features/line_fitter.h"
#include "ply_slam/features/orb_extractor.h"
#include "ply_slam/io/tum_sequence.h"
#include "ply_slam/mapping/mapper.h"
#include "ply_slam/tracking/tracker.h"
#include "shared_data.h"

namespace ply_slam {
namespace {

// A keyframe as another copy of the map first gets it: features and pose, no links.
std::shared_ptr<KeyFrame> unlinked(const KeyFrame& keyframe) {
  auto copy = std::make_shared<KeyFrame>(keyframe);
  copy->map_points.assign(copy->map_points.size(), nullptr);
  copy->map_lines.assign(copy->map_lines.size(), nullptr);
  copy->covisibility.clear();
  copy->parent = nullptr;
  return copy;
}

TEST(MapReplicas, FollowTheTrackerByItsReportAndTheMapperByItsUpdate) {
  const std::string folder = test::sharedPath("data/tum/rgbd_dataset_freiburg1_rpy_150_349");
  SystemConfig config = loadConfig(std::string(PLY_SLAM_SOURCE_DIR) + "/config/tum_fr1.yaml");
  config.lines.enabled = true;
  config.loop.enabled = false;
  const TumSequence sequence(folder);
  const OrbExtractor extractor(config.orb);
  const LineExtractor line_extractor(config.lines);
  const LineFitter line_fitter(config.lines, config.camera);

  Map map;
  Mapper mapper(config.camera, mapperOptions(config), map);
  LandmarkCreator creator(config.camera, config.tracking.max_point_depth, config.lines, map);
  Tracker tracker(config.camera, config.tracking, config.orb, config.lines, map, creator);
  TrackerReport report;
  creator.reportTo(&report);
  std::unique_ptr<Map> mapped = test::copyMap(map);  // as the mapping side left it
  int keyframes = 0, line_fits = 0, fused_depths = 0, changes = 0, culled_keyframes = 0;
  for (size_t i = 0; i < sequence.size() && i < 120; ++i) {
    const RgbdImages images = sequence.load(i, config.camera.depth_factor);
    cv::Mat gray;
    cv::cvtColor(images.rgb, gray, cv::COLOR_BGR2GRAY);
    Frame frame(static_cast<long>(i), images.stamp,
                FrameFeatures::extract(gray, images.depth, config.camera, extractor));
    frame.setLines(
        FrameLines::extract(gray, images.depth, config.camera, line_extractor, line_fitter));
    const TrackingResult result = tracker.track(frame);
    ASSERT_EQ(result.state, TrackingState::kOk) << "frame " << i;
    if (!result.new_keyframe) continue;
    ++keyframes;
    line_fits += static_cast<int>(report.line_fits.size());
    for (const auto& link : report.point_links) fused_depths += link.weight > 0.0;

    LandmarkCreator replayer(config.camera, config.tracking.max_point_depth, config.lines, *mapped);
    replayer.replay(report, unlinked(*result.new_keyframe));
    test::expectSameMap(*mapped, map, "keyframe of frame " + std::to_string(i));
    if (HasFatalFailure()) return;

    report = TrackerReport{};
    std::unique_ptr<Map> tracked = test::copyMap(map);  // as the tracker left it
    MapJournal journal;
    map.journalTo(&journal);
    const KeyFrameInsertionStats stats = mapper.insertKeyFrame(
        result.new_keyframe, [&] { return std::set<long>{tracker.referenceKeyFrame()->id}; });
    map.journalTo(nullptr);
    MapUpdate update = mapper.localUpdate(*result.new_keyframe);
    update.journal = std::move(journal);
    changes += static_cast<int>(update.journal.entries.size());
    culled_keyframes += static_cast<int>(stats.culled_keyframes.size());
    tracked->apply(update);
    test::expectSameMap(*tracked, map, "mapped keyframe of frame " + std::to_string(i), 1e-12);
    if (HasFatalFailure()) return;
    mapped = test::copyMap(map);
  }
  std::cout << keyframes << " keyframes, " << line_fits << " line fits, " << fused_depths
            << " depths fused into old points; " << changes << " changes journaled, "
            << culled_keyframes << " keyframes culled\n";
  // The replay had something to do: keyframes, lines fused between them, depths into old points.
  EXPECT_GE(keyframes, 8);
  EXPECT_GT(line_fits, 100);
  EXPECT_GT(fused_depths, 500);
}

}  // namespace
}  // namespace ply_slam
