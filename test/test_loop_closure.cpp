// Loop closure on the synthetic ring: a corridor walked once round a block, with sensor noise,
// so tracking drifts and only the return to the start can correct it. The same run with and
// without loop closure, against the exact ground truth; and the run with loop closure again with
// the tracker in a copy of the map of its own (MappingMode::kSplit), which must repeat it; and
// with the tracker apart, following the mapping side's updates three keyframes late as
// tracking_node does when mapping_node lags, which must close the loop as well.
#include <gtest/gtest.h>
#include <unistd.h>

#include <deque>
#include <filesystem>
#include <iostream>

#include "default_vocabularies.h"
#include "map_equality.h"
#include "ply_slam/eval/trajectory_metrics.h"
#include "ply_slam/io/tum_sequence.h"
#include "ply_slam/synth/synthetic_sequence.h"
#include "ply_slam/synth/synthetic_sequence_writer.h"
#include "ply_slam/system/mapping_side.h"
#include "ply_slam/system/system.h"
#include "ply_slam/system/system_config.h"

namespace ply_slam {
namespace {

struct RunOutcome {
  size_t lost = 0;
  long loops_closed = 0;
  double ate = 0.0;
  double keyframe_ate = 0.0, end_gap = 0.0;  // of the keyframes (endGap)
  Trajectory trajectory;
};

Trajectory keyFramesOf(const Map& map) {
  Trajectory out;
  for (const auto& kf : map.keyFrames()) out.push_back({kf->stamp, kf->T_wc()});
  return out;
}

// How far the last keyframe is from where the first and the ground truth put it (m): the ring
// ends where it began, so this is the drift a loop closure must take out at the end.
double endGap(const Trajectory& keyframes, const Trajectory& truth) {
  const Trajectory ends{keyframes.front(), keyframes.back()};
  return computeRpeFrames(truth, ends, 1).translation.max;
}

void measureKeyFrames(const Map& map, const TumSequence& sequence, RunOutcome& run) {
  const Trajectory keyframes = keyFramesOf(map);
  run.keyframe_ate = computeAte(sequence.groundTruth(), keyframes).translation.rmse;
  run.end_gap = endGap(keyframes, sequence.groundTruth());
}

RunOutcome track(const TumSequence& sequence, SystemConfig config, bool loop_closure,
                 MappingMode mode = MappingMode::kInline) {
  config.loop.enabled = loop_closure;
  System system(config, mode);
  RunOutcome run;
  for (size_t i = 0; i < sequence.size(); ++i) {
    const FrameResult r = system.process(sequence.load(i, config.camera.depth_factor));
    run.lost += r.tracking.state != TrackingState::kOk;
  }
  if (system.loopCounts()) run.loops_closed = system.loopCounts()->corrected;
  run.trajectory = system.cameraTrajectory();
  run.ate = computeAte(sequence.groundTruth(), run.trajectory).translation.rmse;
  measureKeyFrames(system.map(), sequence, run);
  return run;
}

// The tracker apart (MappingMode::kApart) with a mapping side of its own, as tracking_node and
// mapping_node run them, the tracker following each update `late` keyframes after it was made:
// the tracker makes keyframes in the world as it was before a loop's update reached it.
RunOutcome trackApart(const TumSequence& sequence, SystemConfig config, size_t late) {
  config.loop.enabled = true;
  System tracker(config, MappingMode::kApart);
  MappingSide mapping(config, true, true);
  std::deque<MappingJob> jobs;
  std::deque<std::shared_ptr<const MapUpdate>> updates;
  tracker.setJobSink([&jobs](MappingJob job) { jobs.push_back(std::move(job)); });
  RunOutcome out;
  for (size_t i = 0; i <= sequence.size(); ++i) {
    if (i < sequence.size())
      out.lost += tracker.process(sequence.load(i, config.camera.depth_factor)).tracking.state !=
                  TrackingState::kOk;
    for (; !jobs.empty(); jobs.pop_front()) {
      const MappedKeyFrame mapped = mapping.mapKeyFrame(jobs.front());
      out.loops_closed += mapped.loop_correction != nullptr;
      updates.push_back(mapped.map_update);
    }
    for (; updates.size() > (i < sequence.size() ? late : 0); updates.pop_front())
      tracker.followMapUpdate(*updates.front());
  }
  measureKeyFrames(mapping.map(), sequence, out);
  return out;
}

TEST(LoopClosure, HalvesTheDriftOfOneWalkRoundTheRing) {
  PLY_SLAM_REQUIRE_VOCABULARY(vocabularyPath("", DescriptorKind::kOrb));
  PLY_SLAM_REQUIRE_VOCABULARY(vocabularyPath("", DescriptorKind::kLbd));
  // Per process: two test runs at once (two build trees) must not share the folder.
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("ply_slam_test_ring_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  SynthOptions options;
  options.scene = SceneKind::kRing;
  options.frames = defaultFrames(SceneKind::kRing);
  options.loop = true;
  options.noise = true;
  writeSyntheticSequence(SyntheticSequence(options), dir.string());
  const TumSequence sequence(dir.string());
  const SystemConfig config = loadConfig((dir / "camera.yaml").string());

  const RunOutcome drifting = track(sequence, config, false);
  const RunOutcome closed = track(sequence, config, true);
  const RunOutcome split = track(sequence, config, true, MappingMode::kSplit);
  const RunOutcome apart = trackApart(sequence, config, 3);
  std::filesystem::remove_all(dir);
  std::cout << "ATE without loop closure " << drifting.ate << " m, with " << closed.ate << " m ("
            << closed.loops_closed << " loops closed)\n";
  std::cout << "keyframes without loop closure: ATE " << drifting.keyframe_ate
            << " m, the last one " << drifting.end_gap
            << " m from where the first puts it; apart, updates followed 3 keyframes late: "
            << apart.loops_closed << " loops closed, ATE " << apart.keyframe_ate << " m, "
            << apart.end_gap << " m\n";
  EXPECT_EQ(drifting.lost, 0u);
  EXPECT_EQ(closed.lost, 0u);
  // Measured (docs/RESULTS.md): 0.0340 m without, 0.0153 m with one loop closed.
  EXPECT_GE(drifting.ate, 0.015);  // the scene must drift, or the test says nothing
  EXPECT_GE(closed.loops_closed, 1);
  EXPECT_LE(closed.ate, 0.5 * drifting.ate);
  // The tracker's copy followed every update of the mapping side, the loop's too.
  EXPECT_EQ(split.loops_closed, closed.loops_closed);
  test::expectSameTrajectory(split.trajectory, closed.trajectory);
  // Apart, three keyframes late: the keyframes the tracker made from poses the mapping side had
  // moved since must move with them (MappingSide::moveSinceTracked). Measured (session 45):
  // keyframe ATE 0.0076 m (in line 0.0068 m; 0.0450 m when they did not move), the ends 0.0039 m
  // apart; without loop closure 0.0181 m and 0.073 m.
  EXPECT_EQ(apart.lost, 0u);
  EXPECT_GE(apart.loops_closed, 1);
  EXPECT_LE(apart.end_gap, 0.2 * drifting.end_gap);
  EXPECT_LE(apart.keyframe_ate, 0.5 * drifting.keyframe_ate);
}

}  // namespace
}  // namespace ply_slam
