// mapping_node's copy of the map (MapStore, fed the keyframe packets and map updates the tracker
// publishes) must hold what the System's map holds: scripts/soak.sh found the copy keeping
// every point ever made (212 378 culled ones over the 3 000-frame office) because map updates
// did not say which points had left.
#include <gtest/gtest.h>

#include <set>

#include "default_vocabularies.h"
#include "ply_slam/io/tum_sequence.h"
#include "ply_slam/loop/vocabulary_path.h"
#include "ply_slam/map/map_store.h"
#include "ply_slam/system/system.h"
#include "ply_slam/system/system_config.h"
#include "shared_data.h"

namespace ply_slam {
namespace {

// With the mapping side on its own thread too: its results come with later frames and the rest
// with finishMapping, and nothing may be lost on the way.
class MapStoreFollowsSystem : public testing::TestWithParam<MappingMode> {};

TEST_P(MapStoreFollowsSystem, SamePointsAndKeyFramesAsTheMap) {
  const std::string folder = test::sharedPath("data/tum/rgbd_dataset_freiburg1_xyz_37");
  PLY_SLAM_REQUIRE_SHARED(folder);
  SystemConfig config = loadConfig(std::string(PLY_SLAM_SOURCE_DIR) + "/config/tum_fr1.yaml");
  // Culling is what this checks; place recognition is on so that the mapping thread runs all
  // it runs (under ThreadSanitizer too: scripts/sanitize.sh --thread).
  PLY_SLAM_REQUIRE_VOCABULARY(vocabularyPath("", DescriptorKind::kOrb));
  PLY_SLAM_REQUIRE_VOCABULARY(vocabularyPath("", DescriptorKind::kLbd));
  config.dense.enabled = false;
  config.lines.enabled = true;  // line landmarks must follow too
  System system(config, GetParam());
  const TumSequence sequence(folder);
  MapStore store;
  size_t erased = 0, packets = 0, keyframes_made = 0;
  auto take = [&](const std::vector<MappedKeyFrame>& mapped) {
    for (const MappedKeyFrame& m : mapped) {
      if (!m.packet) continue;  // a global BA after the last keyframe: no loop here
      store.insert(*m.packet);
      store.apply(*m.map_update);
      erased += m.map_update->erased_points.size();
      ++packets;
    }
  };
  for (size_t i = 0; i < sequence.size(); ++i) {
    const FrameResult r = system.process(sequence.load(i, config.camera.depth_factor));
    keyframes_made += r.tracking.new_keyframe != nullptr;
    take(r.mapped);
  }
  take(system.finishMapping());
  EXPECT_EQ(packets, keyframes_made);
  EXPECT_GT(erased, 0u) << "no point was culled: the test proves nothing";
  std::set<long> in_map, in_store;
  for (const auto& p : system.map().mapPoints()) in_map.insert(p->id);
  for (const auto& [id, p] : store.points()) in_store.insert(id);
  EXPECT_EQ(in_store.size(), in_map.size());
  EXPECT_EQ(in_store, in_map);
  std::set<long> keyframes_in_map, keyframes_in_store;
  for (const auto& kf : system.map().keyFrames()) keyframes_in_map.insert(kf->id);
  for (const auto& [id, kf] : store.keyFrames()) keyframes_in_store.insert(id);
  EXPECT_EQ(keyframes_in_store, keyframes_in_map);
  std::set<long> lines_in_map, lines_in_store;
  for (const auto& l : system.map().mapLines()) lines_in_map.insert(l->id);
  for (const auto& [id, l] : store.lines()) lines_in_store.insert(id);
  EXPECT_GT(lines_in_map.size(), 0u);
  EXPECT_EQ(lines_in_store, lines_in_map);
  // The copy's poses are the map's.
  for (const auto& kf : system.map().keyFrames())
    EXPECT_TRUE(store.keyFrames().at(kf->id).T_wc.isApprox(kf->T_wc(), 1e-12)) << kf->id;
}

INSTANTIATE_TEST_SUITE_P(EveryMappingMode, MapStoreFollowsSystem,
                         testing::Values(MappingMode::kInline, MappingMode::kOwnThread,
                                         MappingMode::kSplit, MappingMode::kSplitOwnThread),
                         [](const testing::TestParamInfo<MappingMode>& info) {
                           switch (info.param) {
                             case MappingMode::kInline:
                               return "Inline";
                             case MappingMode::kOwnThread:
                               return "OwnThread";
                             case MappingMode::kSplit:
                               return "Split";
                             default:
                               return "SplitOwnThread";
                           }
                         });

}  // namespace
}  // namespace ply_slam
