// mapping_node's copy of the map (MapStore, fed the keyframe packets and map updates the tracker
// publishes) must hold what the System's map holds: scripts/soak.sh found the copy keeping
// every point ever made (212 378 culled ones over the 3 000-frame office) because map updates
// did not say which points had left.
#include <gtest/gtest.h>

#include <set>

#include "ply_slam/common/config.h"
#include "ply_slam/io/tum_sequence.h"
#include "ply_slam/map/map_store.h"
#include "ply_slam/system/system.h"
#include "shared_data.h"

namespace ply_slam {
namespace {

TEST(MapStoreFollowsSystem, SamePointsAndKeyFramesAsTheMap) {
  const std::string folder = test::sharedPath("data/tum/rgbd_dataset_freiburg1_xyz_37");
  PLY_SLAM_REQUIRE_SHARED(folder);
  SystemConfig config = loadConfig(std::string(PLY_SLAM_SOURCE_DIR) + "/config/tum_fr1.yaml");
  config.loop.enabled = false;  // culling is what matters here, not the vocabularies
  config.dense.enabled = false;
  System system(config);
  const TumSequence sequence(folder);
  MapStore store;
  size_t erased = 0;
  for (size_t i = 0; i < sequence.size(); ++i) {
    const FrameResult r = system.process(sequence.load(i, config.camera.depth_factor));
    if (r.keyframe_packet) store.insert(*r.keyframe_packet);
    if (r.map_update) {
      store.apply(*r.map_update);
      erased += r.map_update->erased_points.size();
    }
  }
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
}

}  // namespace
}  // namespace ply_slam
