// A copy of the map that follows the tracker by its reports (TrackerReport: what it did between
// two keyframes, by id) and the mapping side by its updates (MapUpdate: its journal of links,
// merges and erasures, and the values it left), as the other process of a two-process split
// would, equals the map: real fr1_rpy frames with lines, and a synthetic corridor walked round
// to its start with loop closure, tracked and mapped as System does in line (fusion, local BA,
// culling, loop correction).
#include <gtest/gtest.h>

#include <deque>
#include <iostream>
#include <opencv2/imgproc.hpp>
#include <optional>
#include <stdexcept>

#include "default_vocabularies.h"
#include "map_equality.h"
#include "ply_slam/features/line_extractor.h"
#include "ply_slam/features/line_fitter.h"
#include "ply_slam/features/orb_extractor.h"
#include "ply_slam/io/tum_sequence.h"
#include "ply_slam/map/by_id.h"
#include "ply_slam/mapping/mapper.h"
#include "ply_slam/synth/synthetic_sequence.h"
#include "ply_slam/synth/synthetic_sequence_writer.h"
#include "ply_slam/system/key_frame_packet_builder.h"
#include "ply_slam/system/mapping_side.h"
#include "ply_slam/system/system.h"
#include "ply_slam/system/system_config.h"
#include "ply_slam/tracking/tracker.h"
#include "pose_test_helpers.h"
#include "replica_run.h"
#include "shared_data.h"
#include "temp_dir.h"

namespace ply_slam {
namespace {

// A small map: two keyframes sharing one point, each with one keypoint.
struct TwoKeyFrames {
  Map map;
  std::shared_ptr<KeyFrame> a = std::make_shared<KeyFrame>(), b = std::make_shared<KeyFrame>();
  std::shared_ptr<MapPoint> point;
  TwoKeyFrames() {
    for (auto& kf : {a, b}) {
      kf->map_points.resize(1);
      map.addKeyFrame(kf);
    }
    point = map.createMapPoint(Eigen::Vector3d(0, 0, 2), cv::Mat(), a->id);
    map.addObservation(*a, 0, point);
    map.addObservation(*b, 0, point);
  }
};

TEST(MapReplicas, AReportOfAnotherKeyFrameIsRefused) {
  TwoKeyFrames copy;
  TrackerReport report;
  report.keyframe = 5;
  report.points[copy.point->id].found = 3;
  auto keyframe = std::make_shared<KeyFrame>();
  keyframe->id = 6;
  LandmarkCreator creator(test::makeCamera(), 5.0, LineOptions(), copy.map);
  EXPECT_THROW(creator.replay(report, keyframe), std::invalid_argument);
  EXPECT_EQ(copy.map.numKeyFrames(), 2u);
  EXPECT_EQ(copy.point->found, 0);
}

TEST(MapReplicas, JournalEntriesNamingWhatTheCopyHasNotAreLeftOut) {
  TwoKeyFrames original, copy;
  MapJournal journal;
  original.map.journalTo(&journal);
  original.map.removeObservation(*original.b, 0);
  original.map.removeObservation(*original.b, 0);  // nothing linked: not journaled
  original.map.erasePoint(original.point);
  original.map.journalTo(nullptr);
  ASSERT_EQ(journal.entries.size(), 2u);
  EXPECT_TRUE(original.point->bad);
  MapJournal foreign = journal;
  for (auto& e : foreign.entries) e.keyframe = e.point = 99;  // ids the copy does not hold
  copy.map.replay(foreign);
  EXPECT_FALSE(copy.point->bad);
  EXPECT_EQ(copy.point->observations(), 2);
  copy.map.replay(journal);
  EXPECT_TRUE(copy.point->bad);
  EXPECT_EQ(copy.a->map_points[0], nullptr);
  EXPECT_EQ(copy.b->covisibility.size(), 0u);
}

// fr1_rpy_150_349 with lines on: real frames where lines fuse between keyframes.
std::string rpyFolder() { return test::sharedPath("data/tum/rgbd_dataset_freiburg1_rpy_150_349"); }
SystemConfig rpyConfig() {
  SystemConfig config = loadConfig(std::string(PLY_SLAM_SOURCE_DIR) + "/config/tum_fr1.yaml");
  config.lines.enabled = true;
  return config;
}

// The corridor walked once round and back to its start (as ply_slam_synth --loop renders it).
constexpr int kLoopFrames = 600;

using test::ReplicaRun;

TEST(MapReplicas, FollowTheTrackerByItsReportAndTheMapperByItsUpdate) {
  SystemConfig config = rpyConfig();
  config.loop.enabled = false;
  const TumSequence sequence(rpyFolder());
  ReplicaRun run(config, 1);
  for (size_t i = 0; i < sequence.size() && i < 120; ++i) {
    run.process(static_cast<long>(i), sequence.load(i, config.camera.depth_factor));
    if (HasFatalFailure()) return;
  }
  std::cout << run.keyframes << " keyframes, " << run.line_fits << " line fits, "
            << run.fused_depths << " depths fused into old points; " << run.changes
            << " changes journaled, " << run.culled_keyframes << " keyframes culled\n";
  // The replay had something to do: keyframes, lines fused between them, depths into old points.
  EXPECT_GE(run.keyframes, 8);
  EXPECT_GT(run.line_fits, 100);
  EXPECT_GT(run.fused_depths, 500);
}

// The system with the tracker in a copy of the map of its own (MappingMode::kSplit: the copies
// follow each other by reports and updates) tracks and maps as it does in one map, bit for bit.
TEST(MapReplicas, ASystemTrackingInACopyRepeatsTheRunInOneMap) {
  SystemConfig config = rpyConfig();
  config.loop.enabled = false;
  const TumSequence sequence(rpyFolder());
  System one_map(config, MappingMode::kInline), split(config, MappingMode::kSplit);
  long keyframes = 0;
  for (size_t i = 0; i < sequence.size() && i < 120; ++i) {
    const RgbdImages images = sequence.load(i, config.camera.depth_factor);
    const FrameResult a = one_map.process(images), b = split.process(images);
    ASSERT_EQ(a.tracking.state, b.tracking.state) << "frame " << i;
    ASSERT_EQ(a.mapped.size(), b.mapped.size()) << "frame " << i;
    keyframes += static_cast<long>(b.mapped.size());
  }
  EXPECT_GE(keyframes, 8);
  test::expectSameTrajectory(split.cameraTrajectory(), one_map.cameraTrajectory());
  test::expectSameTrajectory(split.keyFrameTrajectory(), one_map.keyFrameTrajectory());
  test::expectSameMap(split.map(), one_map.map(), "after 120 frames");
}

// With the mapping side on a thread of its own the tracker's copy follows each update a few
// frames late and the tracker goes on meanwhile; once the mapping side has caught up, the copy
// holds the same keyframes where the mapping side put them and the same landmarks.
TEST(MapReplicas, ATrackerOnItsOwnThreadFollowsTheMapperOnAnother) {
  const SystemConfig config = rpyConfig();
  const TumSequence sequence(rpyFolder());
  System split(config, MappingMode::kSplitOwnThread);
  size_t lost = 0;
  for (size_t i = 0; i < sequence.size(); ++i)
    lost += split.process(sequence.load(i, config.camera.depth_factor)).tracking.state !=
            TrackingState::kOk;
  split.finishMapping();
  EXPECT_EQ(lost, 0u);
  const Map &copy = split.trackerMap(), &map = split.map();
  ASSERT_NE(&copy, &map);
  // Every keyframe where the mapping side put it, every point where it put it.
  const auto kfs_copy = copy.keyFrames(), kfs_map = map.keyFrames();
  ASSERT_EQ(kfs_copy.size(), kfs_map.size());
  for (size_t k = 0; k < kfs_map.size(); ++k) {
    ASSERT_EQ(kfs_copy[k]->id, kfs_map[k]->id);
    EXPECT_TRUE(kfs_copy[k]->T_cw.matrix() == kfs_map[k]->T_cw.matrix()) << kfs_map[k]->id;
  }
  const auto points_copy = byId(copy.mapPoints());
  size_t links = 0, other_links = 0;
  for (const auto& p : map.mapPoints()) {
    const auto q = points_copy.find(p->id);
    ASSERT_NE(q, points_copy.end()) << "point " << p->id;
    EXPECT_EQ(q->second->position, p->position) << "point " << p->id;
  }
  EXPECT_EQ(points_copy.size(), map.mapPoints().size());
  // Who sees what, link for link: the copy went on linking while the mapping side merged, but
  // each update carries the links the mapping side made for its keyframe, which the copy takes.
  auto id = [](const std::shared_ptr<MapPoint>& p) { return p ? p->id : -1L; };
  for (size_t k = 0; k < kfs_map.size(); ++k)
    for (size_t i = 0; i < kfs_map[k]->map_points.size(); ++i) {
      links += kfs_map[k]->map_points[i] != nullptr;
      const bool differs = id(kfs_map[k]->map_points[i]) != id(kfs_copy[k]->map_points[i]);
      other_links += differs;
      if (differs && other_links <= 5)
        ADD_FAILURE() << "keyframe " << kfs_map[k]->id << " keypoint " << i << ": point "
                      << id(kfs_map[k]->map_points[i]) << " on the mapping side, "
                      << id(kfs_copy[k]->map_points[i]) << " in the copy";
    }
  std::cout << kfs_map.size() << " keyframes, " << points_copy.size() << " points, " << links
            << " links, " << other_links << " of them not in the copy or otherwise there\n";
  EXPECT_GT(links, 5000u);
  EXPECT_EQ(other_links, 0u);
}

// A tracker apart that follows an update late has made keyframes (and landmarks with them) on
// top of the keyframe the update moved: they move as that one moved, rigidly, and nothing of
// what the update leaves alone moves.
TEST(MapReplicas, KeyFramesTheMappingSideHasNotSeenMoveWithTheOneBefore) {
  const TempDir dir;
  SynthOptions options;
  options.scene = SceneKind::kOffice;
  options.frames = 150;
  options.noise = true;  // local BA then moves the keyframes
  writeSyntheticSequence(SyntheticSequence(options), dir.path().string());
  const TumSequence sequence(dir.path().string());
  const SystemConfig config = loadConfig(dir.file("camera.yaml"));
  System tracker(config, MappingMode::kApart);
  MappingSide mapping(config, true, true);
  std::deque<std::shared_ptr<const MapUpdate>> updates;
  tracker.setJobSink(
      [&](MappingJob job) { updates.push_back(mapping.mapKeyFrame(job).map_update); });
  const Map& copy = tracker.trackerMap();
  size_t checked = 0;
  for (size_t i = 0; i < sequence.size(); ++i) {
    ASSERT_EQ(tracker.process(sequence.load(i, config.camera.depth_factor)).tracking.state,
              TrackingState::kOk);
    if (updates.size() <= 3) continue;  // followed three keyframes late
    const std::shared_ptr<const MapUpdate> followed = updates.front();
    updates.pop_front();
    const MapUpdate& update = *followed;
    long newest = -1;
    for (const auto& pose : update.keyframes) newest = std::max(newest, pose.id);
    std::map<long, Eigen::Isometry3d> before;
    for (const auto& kf : copy.keyFrames()) before[kf->id] = kf->T_wc();
    std::map<long, Eigen::Vector3d> points_before;
    for (const auto& p : copy.mapPoints())
      if (p->first_keyframe_id > newest) points_before[p->id] = p->position;
    tracker.followMapUpdate(update);
    if (newest < 0) continue;
    const auto after = byId(copy.keyFrames());
    const Eigen::Isometry3d moved = after.at(newest)->T_wc() * before.at(newest).inverse();
    std::set<long> in_update;
    for (const auto& pose : update.keyframes) in_update.insert(pose.id);
    for (const auto& [id, T_wc] : before) {
      const auto kf = after.find(id);
      if (kf == after.end() || in_update.count(id)) continue;
      const Eigen::Isometry3d expected = id > newest ? moved * T_wc : T_wc;
      EXPECT_TRUE(kf->second->T_wc().isApprox(expected, 1e-9))
          << "keyframe " << id << " after the update of keyframe " << newest;
      checked += id > newest;
    }
    for (const auto& p : copy.mapPoints()) {
      const auto was = points_before.find(p->id);
      if (was == points_before.end()) continue;
      EXPECT_LT((p->position - moved * was->second).norm(), 1e-9) << "point " << p->id;
    }
    if (HasFailure()) return;
  }
  std::cout << checked << " keyframes carried along\n";
  EXPECT_GE(checked, 20u);
}

// A mapping side that stalls (overloaded, or busy with a loop): the tracker hands over no more
// than tracking.keyframe_max_unmapped + 1 keyframes it has not answered, goes on tracking
// against the map it has, and makes keyframes again once the answers come.
TEST(MapReplicas, TheTrackerHoldsBackKeyFramesWhileTheMappingSideIsBehind) {
  const TempDir dir;
  SynthOptions options;
  options.scene = SceneKind::kOffice;
  options.frames = 150;
  options.noise = true;
  writeSyntheticSequence(SyntheticSequence(options), dir.path().string());
  const TumSequence sequence(dir.path().string());
  SystemConfig config = loadConfig(dir.file("camera.yaml"));
  const size_t bound = static_cast<size_t>(config.tracking.keyframe_max_unmapped);
  ASSERT_EQ(bound, 3u);  // the shipped default

  // Stalled for the first 60 frames (a tracker wants a keyframe every 5 frames at most), then
  // one job mapped per frame; with `forget`, nobody maps and from then on the tracker is told
  // after each frame that its jobs went nowhere (as tracking_node does without a subscriber).
  struct Outcome {
    size_t jobs_in_stall = 0, jobs = 0, held_back = 0, most_waiting = 0, lost = 0;
  };
  const auto run = [&](int max_unmapped, bool forget) {
    config.tracking.keyframe_max_unmapped = max_unmapped;
    System tracker(config, MappingMode::kApart);
    MappingSide mapping(config, true, true);
    std::deque<MappingJob> waiting;
    tracker.setJobSink([&](MappingJob job) { waiting.push_back(std::move(job)); });
    Outcome out;
    for (size_t i = 0; i < sequence.size(); ++i) {
      const FrameResult r = tracker.process(sequence.load(i, config.camera.depth_factor));
      out.lost += r.tracking.state != TrackingState::kOk;
      out.jobs += r.tracking.new_keyframe != nullptr;
      out.held_back += r.tracking.keyframe_held_back;
      out.most_waiting = std::max(out.most_waiting, waiting.size());
      if (i + 1 == 60) out.jobs_in_stall = out.jobs;
      if (forget && i + 1 >= 60) {
        tracker.forgetUnansweredJobs();
        waiting.clear();
      }
      EXPECT_EQ(tracker.mappingBacklog(), waiting.size());
      if (i + 1 < 60 || forget || waiting.empty()) continue;
      tracker.followMapUpdate(*mapping.mapKeyFrame(waiting.front()).map_update);
      waiting.pop_front();
    }
    return out;
  };
  const Outcome bounded = run(static_cast<int>(bound), false);
  const Outcome unbounded = run(1000, false);
  const Outcome forgotten = run(static_cast<int>(bound), true);
  std::cout << "jobs during the stall / in all / frames held back / most waiting: bounded "
            << bounded.jobs_in_stall << " / " << bounded.jobs << " / " << bounded.held_back << " / "
            << bounded.most_waiting << "; unbounded " << unbounded.jobs_in_stall << " / "
            << unbounded.jobs << " / " << unbounded.held_back << " / " << unbounded.most_waiting
            << "; forgotten " << forgotten.jobs_in_stall << " / " << forgotten.jobs << "\n";
  EXPECT_EQ(bounded.lost, 0u);
  EXPECT_EQ(bounded.jobs_in_stall, bound + 1);
  EXPECT_EQ(bounded.most_waiting, bound + 1);
  EXPECT_GT(bounded.held_back, 0u);
  // The answers came: keyframes again (as many after the stall as without it, within 3).
  EXPECT_GE(bounded.jobs - bounded.jobs_in_stall + 3, unbounded.jobs - unbounded.jobs_in_stall);
  // Without the bound the stall piles the jobs up: the test can tell.
  EXPECT_GT(unbounded.jobs_in_stall, bound + 4);
  EXPECT_EQ(unbounded.held_back, 0u);
  // Forgotten (no mapping side listens): the tracker makes its keyframes on.
  EXPECT_EQ(forgotten.lost, 0u);
  EXPECT_GE(forgotten.jobs, bounded.jobs_in_stall + 10);
}

// Loop corrections (rigid moves, fusion across the loop, the pose graph, the global BA written
// back) reach the tracker's copy as the whole map's values and the journal of the merges.
TEST(MapReplicas, FollowTheMapperThroughLoopCorrections) {
  PLY_SLAM_REQUIRE_VOCABULARY(vocabularyPath("", DescriptorKind::kOrb));
  PLY_SLAM_REQUIRE_VOCABULARY(vocabularyPath("", DescriptorKind::kLbd));
  const TempDir dir;
  SynthOptions options;
  options.scene = SceneKind::kCorridor;
  options.frames = kLoopFrames;
  options.loop = true;
  writeSyntheticSequence(SyntheticSequence(options), dir.path().string());
  const TumSequence sequence(dir.path().string());
  SystemConfig config = loadConfig(dir.file("camera.yaml"));
  config.lines.enabled = true;
  config.loop.enabled = true;
  // The corridor's end closes a loop at almost every keyframe (15 with the default 10 between,
  // 218 s of this test); a few of them cover every step of the correction.
  config.loop_correction.min_keyframes_between = 50;
  ReplicaRun run(config, 25);
  for (size_t i = 0; i < sequence.size(); ++i) {
    run.process(static_cast<long>(i), sequence.load(i, config.camera.depth_factor));
    if (HasFatalFailure()) return;
  }
  std::cout << run.keyframes << " keyframes, " << run.loops << " loops closed, " << run.changes
            << " changes journaled, " << run.culled_keyframes << " keyframes culled\n";
  EXPECT_GE(run.loops, 1);
}

}  // namespace
}  // namespace ply_slam
