// Loop closure on the synthetic ring: a corridor walked once round a block, with sensor noise,
// so tracking drifts and only the return to the start can correct it. The same run with and
// without loop closure, against the exact ground truth; and the run with loop closure again with
// the tracker in a copy of the map of its own (MappingMode::kSplit), which must repeat it.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <iostream>

#include "default_vocabularies.h"
#include "map_equality.h"
#include "ply_slam/common/config.h"
#include "ply_slam/eval/trajectory_metrics.h"
#include "ply_slam/io/tum_sequence.h"
#include "ply_slam/synth/synthetic_sequence.h"
#include "ply_slam/synth/synthetic_sequence_writer.h"
#include "ply_slam/system/system.h"

namespace ply_slam {
namespace {

struct RunOutcome {
  size_t lost = 0;
  long loops_closed = 0;
  double ate = 0.0;
  Trajectory trajectory;
};

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
  return run;
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
  std::filesystem::remove_all(dir);
  std::cout << "ATE without loop closure " << drifting.ate << " m, with " << closed.ate << " m ("
            << closed.loops_closed << " loops closed)\n";
  EXPECT_EQ(drifting.lost, 0u);
  EXPECT_EQ(closed.lost, 0u);
  // Measured (docs/RESULTS.md): 0.0340 m without, 0.0153 m with one loop closed.
  EXPECT_GE(drifting.ate, 0.015);  // the scene must drift, or the test says nothing
  EXPECT_GE(closed.loops_closed, 1);
  EXPECT_LE(closed.ate, 0.5 * drifting.ate);
  // The tracker's copy followed every update of the mapping side, the loop's too.
  EXPECT_EQ(split.loops_closed, closed.loops_closed);
  test::expectSameTrajectory(split.trajectory, closed.trajectory);
}

}  // namespace
}  // namespace ply_slam
