// MessageSequence: what a receiver of numbered messages missed; MapStore::restore: the map
// mapping_node gets back from the tracker after it missed some.
#include <gtest/gtest.h>

#include "ply_slam/common/message_sequence.h"
#include "ply_slam/map/map_store.h"

namespace ply_slam {
namespace {

TEST(MessageSequence, CountsGapsRepeatsAndLateStarts) {
  MessageSequence late;
  EXPECT_EQ(late.receive(5), 5u);  // started late: 0..4 went by
  EXPECT_EQ(late.receive(6), 0u);
  EXPECT_EQ(late.receive(9), 2u);  // 7, 8 lost
  EXPECT_EQ(late.missed(), 7u);
  EXPECT_EQ(late.receive(8), 0u);  // out of order: not a gap, counted as repeated
  EXPECT_EQ(late.repeated(), 1u);
  EXPECT_EQ(late.expected(), 10u);
  late.resynchronise(12);  // the sender filled the gaps and has sent up to 11 meanwhile
  EXPECT_EQ(late.missed(), 0u);
  EXPECT_EQ(late.receive(12), 0u);
  late.resynchronise(11);  // an older snapshot than the messages already seen: keeps its place
  EXPECT_EQ(late.expected(), 13u);
  MessageSequence on_time;
  EXPECT_EQ(on_time.receive(0), 0u);
  EXPECT_EQ(on_time.receive(1), 0u);
  EXPECT_EQ(on_time.missed(), 0u);
}

KeyFramePacket packet(long id, double x) {
  KeyFramePacket p;
  p.id = id;
  p.stamp = id;
  p.T_wc.translation() = Eigen::Vector3d(x, 0, 0);
  p.points = {{10 * id, {x, 1, 2}}};
  return p;
}

TEST(MapStore, RestoreTakesTheTrackersMapAndKeepsWhatCameAfterIt) {
  MapStore store;
  for (long id : {0, 1, 2, 7}) store.insert(packet(id, 0.0));  // 3..6 missed, 7 came after
  // The tracker's map when it answered: 2 was culled meanwhile, 3..6 exist, all moved.
  const std::vector<long> erased =
      store.restore({packet(0, 1.0), packet(1, 1.0), packet(3, 1.0), packet(6, 1.0)});
  EXPECT_EQ(erased, std::vector<long>{2});
  ASSERT_EQ(store.keyFrames().size(), 5u);  // 0 1 3 6 7
  EXPECT_EQ(store.keyFrames().count(2), 0u);
  EXPECT_EQ(store.keyFrames().at(3).T_wc.translation().x(), 1.0);
  EXPECT_EQ(store.keyFrames().at(7).T_wc.translation().x(), 0.0);  // newer: kept as it was
  EXPECT_EQ(store.points().count(20), 0u);  // the culled keyframe's landmark is gone
  EXPECT_EQ(store.points().at(30).position.x(), 1.0);
  EXPECT_EQ(store.points().count(70), 1u);
}

}  // namespace
}  // namespace ply_slam
