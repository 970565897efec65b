// Dynamic rejection in the running system, on the synthetic office with people
// walking through it: exact masks say which features lie on a walker.
#include <gtest/gtest.h>

#include <iostream>

#include "ply_slam/eval/feature_classification.h"
#include "ply_slam/synth/synthetic_sequence.h"
#include "ply_slam/system/system.h"

namespace ply_slam {
namespace {

struct Outcome {
  FeatureClassification classification;
  long dynamic_lines = 0;
  int lost = 0;
};

// Runs the system over `frames` frames of the office with `walkers` people; `labels` gives
// the system the walkers' exact masks as "person" instances.
Outcome runOffice(int walkers, const std::string& mode, bool labels, bool lines = false) {
  SynthOptions o;
  o.walkers = walkers;
  o.frames = 60;
  o.noise = true;
  o.seed = 7;
  const SyntheticSequence sequence(o);
  SystemConfig config;
  config.camera = sequence.sensorCamera();
  config.dynamic.mode = parseDynamicMode(mode);
  config.lines.enabled = lines;
  System system(config);
  Outcome outcome;
  for (int i = 0; i < sequence.size(); ++i) {
    const RenderedFrame f = sequence.render(i);
    RgbdImages images;
    images.stamp = images.depth_stamp = sequence.stamp(i);
    images.rgb = f.rgb;
    images.depth = f.depth;
    std::vector<Instance> instances;
    for (int id = 1; id <= walkers && labels; ++id) {
      cv::Mat mask = f.instance == id;
      if (cv::countNonZero(mask) > 0) instances.push_back({id, "person", 1.0f, mask});
    }
    const FrameResult r = system.process(images, instances);
    outcome.lost += r.tracking.state != TrackingState::kOk;
    outcome.dynamic_lines += static_cast<long>(r.dynamic_lines);
    const cv::Mat walker_pixels = (f.instance != 0) & (f.instance < Scene::kFirstObjectInstance);
    outcome.classification.add(r.features, walker_pixels);
  }
  const auto& c = outcome.classification;
  std::cout << "[ measured ] " << mode << (labels ? " + masks" : "") << ": walker features "
            << c.walkerFeatures() << ", kept " << 100 * c.walkerKeptShare() << " %, used "
            << 100 * c.walkerInlierShare() << " %; static " << c.staticFeatures() << ", dropped "
            << 100 * c.staticDroppedShare() << " %; lines dropped " << outcome.dynamic_lines
            << "; lost " << outcome.lost << "\n";
  return outcome;
}

TEST(DynamicRejection, FullModeKeepsWalkersOutAndTheRoomIn) {
  const Outcome full = runOffice(2, "full", true, true);
  ASSERT_GT(full.classification.walkerFeatures(), 500);
  EXPECT_LE(full.classification.walkerInlierShare(), 0.02);   // target in docs/RESULTS.md
  EXPECT_LE(full.classification.staticDroppedShare(), 0.10);  // target in docs/RESULTS.md
  EXPECT_GT(full.dynamic_lines, 0);  // lines with an end on a walker go too (§3.2 step 5)
  EXPECT_EQ(full.lost, 0);
}

TEST(DynamicRejection, GeometryAloneCatchesWalkersAndLeavesAStaticRoomAlone) {
  const Outcome off = runOffice(2, "off", false);
  const Outcome geometric = runOffice(2, "geometric", false);
  // Without labels the Delaunay check still drops a part of the walker features that the pose
  // optimisation would otherwise have used (those it can match across the baseline; measured
  // 0.68 of the share without it). Labels do the rest, in full mode.
  EXPECT_LT(geometric.classification.walkerInlierShare(),
            0.85 * off.classification.walkerInlierShare());
  // In a room where nothing moves it drops next to nothing.
  const Outcome still = runOffice(0, "geometric", false);
  EXPECT_LE(still.classification.staticDroppedShare(), 0.03);
}

}  // namespace
}  // namespace ply_slam
