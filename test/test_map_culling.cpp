// Erasing keyframes and retiring points on small hand-built maps whose counts are known:
// Map::eraseKeyFrame, KeyFrameCuller (ORB-SLAM's redundancy rule) and MapPointCuller.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <memory>
#include <set>
#include <vector>

#include "ply_slam/map/map.h"
#include "ply_slam/mapping/key_frame_culler.h"
#include "ply_slam/mapping/map_point_culler.h"

namespace ply_slam {
namespace {

const std::vector<double> kScales{1.0, 1.2, 1.44, 1.728};

// Keyframes with one keypoint per point of the map (keypoint i observes point i, when it
// does), each keyframe the child of the one before it unless told otherwise.
class HandMap {
 public:
  explicit HandMap(int points) {
    for (int i = 0; i < points; ++i)
      points_.push_back(map_.createMapPoint(Eigen::Vector3d(i, 0, 3), cv::Mat(), 0));
  }

  std::shared_ptr<KeyFrame> addKeyFrame(KeyFrame* parent) {
    auto kf = std::make_shared<KeyFrame>();
    kf->features.scales = &kScales;
    kf->features.keypoints.resize(points_.size());
    kf->map_points.resize(points_.size());
    kf->map_lines.resize(1);
    kf->parent = parent;
    map_.addKeyFrame(kf);
    keyframes_.push_back(kf);
    return kf;
  }
  // n keyframes, each the child of the one before; the first is the root.
  void addChain(int n) {
    for (int k = 0; k < n; ++k) addKeyFrame(keyframes_.empty() ? nullptr : keyframes_.back().get());
  }
  // Keyframes k sees points [first, last) at pyramid `level`.
  void see(int k, int first, int last, int level = 0) {
    for (int i = first; i < last; ++i) {
      keyframes_[k]->features.keypoints[i].octave = level;
      map_.addObservation(*keyframes_[k], i, points_[i]);
    }
  }

  Map map_;
  std::vector<std::shared_ptr<MapPoint>> points_;
  std::vector<std::shared_ptr<KeyFrame>> keyframes_;
};

// Covisibility as it should be: the good points each pair of keyframes shares.
std::map<const KeyFrame*, int> recountedCovisibility(const KeyFrame& kf) {
  std::map<const KeyFrame*, int> counts;
  for (const auto& p : kf.map_points) {
    if (!p) continue;
    for (const auto& o : p->observers)
      if (o.keyframe != &kf) ++counts[o.keyframe];
  }
  return counts;
}

// Every link and observation names keyframes in the map, both ways, with the right counts,
// and every parent chain ends at the first keyframe.
void expectConsistent(const Map& map) {
  const auto keyframes = map.keyFrames();
  const std::set<const KeyFrame*> in_map = [&] {
    std::set<const KeyFrame*> s;
    for (const auto& kf : keyframes) s.insert(kf.get());
    return s;
  }();
  for (const auto& kf : keyframes) {
    std::map<const KeyFrame*, int> links(kf->covisibility.begin(), kf->covisibility.end());
    EXPECT_EQ(links, recountedCovisibility(*kf)) << "keyframe " << kf->id;
    for (const auto& [other, shared] : kf->covisibility) {
      EXPECT_TRUE(in_map.count(other)) << "keyframe " << kf->id;
      EXPECT_EQ(other->covisibility.at(kf.get()), shared);
    }
    for (size_t i = 0; i < kf->map_points.size(); ++i) {
      const auto& p = kf->map_points[i];
      if (!p) continue;
      EXPECT_FALSE(p->bad) << "a bad point stays linked to keyframe " << kf->id;
      int listed = 0;
      for (const auto& o : p->observers) listed += o.keyframe == kf.get() && o.index == i;
      EXPECT_EQ(listed, 1);
    }
    const KeyFrame* node = kf.get();
    for (size_t steps = 0; node->parent && steps <= keyframes.size(); ++steps) {
      node = node->parent;
      EXPECT_TRUE(in_map.count(node)) << "keyframe " << kf->id << " has an erased ancestor";
    }
    EXPECT_EQ(node, keyframes.front().get()) << "keyframe " << kf->id << " is not in the tree";
  }
  for (const auto& p : map.mapPoints())
    for (const auto& o : p->observers) EXPECT_TRUE(in_map.count(o.keyframe));
}

TEST(SpanningTreeParent, IsTheOlderKeyFrameSharingTheMost) {
  HandMap m(10);
  m.addChain(3);
  m.see(0, 0, 3);  // keyframe 1 shares 3 points with 0 ...
  m.see(1, 0, 10);
  m.see(2, 2, 10);  // ... and 8 with the newer 2 (made by the tracker before 1 was inserted)
  EXPECT_EQ(m.keyframes_[1]->bestCovisible(1).front(), m.keyframes_[2].get());
  EXPECT_EQ(m.keyframes_[1]->bestOlderCovisible(), m.keyframes_[0].get());
  EXPECT_EQ(m.keyframes_[2]->bestOlderCovisible(), m.keyframes_[1].get());
  EXPECT_EQ(m.keyframes_[0]->bestOlderCovisible(), nullptr);
}

TEST(EraseKeyFrame, UnlinksEverythingAndKeepsTheTreeRooted) {
  HandMap h(12);
  h.addChain(3);                         // 0 (the root) <- 1 <- 2
  h.addKeyFrame(h.keyframes_[1].get());  // 3
  h.addKeyFrame(h.keyframes_[2].get());  // 4
  h.see(0, 0, 2);                        // points 0-1: keyframes 0, 1, 2
  h.see(1, 0, 8);                        // 2-3: 1, 2, 3; 4-5: 1, 3; 6-7: 1 only
  h.see(2, 0, 4);
  h.see(3, 2, 6);
  h.see(2, 8, 12);  // 8-11: 2, 3, 4
  h.see(3, 8, 12);
  h.see(4, 8, 12);
  auto line = std::make_shared<MapLine>();
  line->observations = 1;
  h.keyframes_[1]->map_lines[0] = line;
  ASSERT_EQ(h.keyframes_[2]->covisibility.at(h.keyframes_[1].get()), 4);

  ASSERT_TRUE(h.map_.eraseKeyFrame(*h.keyframes_[1], 2));
  EXPECT_EQ(h.map_.numKeyFrames(), 4u);
  EXPECT_TRUE(h.keyframes_[1]->bad);
  EXPECT_TRUE(h.keyframes_[1]->covisibility.empty());
  EXPECT_EQ(h.keyframes_[1]->parent, nullptr);
  for (const auto& p : h.keyframes_[1]->map_points) EXPECT_EQ(p, nullptr);
  EXPECT_TRUE(line->bad);  // its only observer is gone
  // Seen by two keyframes still: kept. Left with one (4-5) or none (6-7): bad.
  for (int i : {0, 1, 2, 3, 8}) EXPECT_FALSE(h.points_[i]->bad) << "point " << i;
  for (int i : {4, 5, 6, 7}) EXPECT_TRUE(h.points_[i]->bad) << "point " << i;
  EXPECT_EQ(h.points_[0]->observations(), 2);
  EXPECT_EQ(h.keyframes_[3]->covisibility.at(h.keyframes_[2].get()), 6);  // points 2-3, 8-11
  EXPECT_EQ(h.keyframes_[0]->covisibility.at(h.keyframes_[2].get()), 2);
  // Children of 1: 2 shares two points with 0 and goes there; 3 shares none with 0 but six
  // with 2, so it follows 2 rather than the grandparent.
  EXPECT_EQ(h.keyframes_[2]->parent, h.keyframes_[0].get());
  EXPECT_EQ(h.keyframes_[3]->parent, h.keyframes_[2].get());
  EXPECT_EQ(h.keyframes_[4]->parent, h.keyframes_[2].get());
  expectConsistent(h.map_);
  EXPECT_EQ(h.map_.removeBadLandmarks(), 4u);
}

TEST(EraseKeyFrame, AChildSharingNothingGoesToTheGrandparent) {
  HandMap h(4);
  h.addChain(3);
  h.see(0, 0, 2);
  h.see(1, 0, 4);
  h.see(2, 2, 4);
  ASSERT_TRUE(h.map_.eraseKeyFrame(*h.keyframes_[1], 1));
  EXPECT_EQ(h.keyframes_[2]->parent, h.keyframes_[0].get());
  expectConsistent(h.map_);
}

// A map read from a file is the only owner of its keyframes: erasing one must not write to it
// after the container let go of it (AddressSanitizer caught that in a loaded-map run).
TEST(EraseKeyFrame, HandsBackAKeyFrameTheMapOwnedAlone) {
  HandMap h(4);
  h.addChain(3);
  h.see(0, 0, 4);
  h.see(1, 0, 4);
  h.see(2, 0, 4);
  KeyFrame& middle = *h.keyframes_[1];
  h.keyframes_[1].reset();  // the map's reference is the last one now
  const std::shared_ptr<KeyFrame> erased = h.map_.eraseKeyFrame(middle, 1);
  ASSERT_NE(erased, nullptr);
  EXPECT_EQ(erased.get(), &middle);
  EXPECT_EQ(erased.use_count(), 1);
  EXPECT_TRUE(erased->bad);
  EXPECT_EQ(erased->parent, nullptr);
  EXPECT_EQ(h.map_.numKeyFrames(), 2u);
}

TEST(EraseKeyFrame, RefusesTheFirstKeyFrameAndStrangers) {
  HandMap h(2);
  h.addChain(2);
  h.see(0, 0, 2);
  h.see(1, 0, 2);
  EXPECT_FALSE(h.map_.eraseKeyFrame(*h.keyframes_[0], 2));
  auto stranger = std::make_shared<KeyFrame>();
  stranger->parent = h.keyframes_[0].get();
  EXPECT_FALSE(h.map_.eraseKeyFrame(*stranger, 2));
  EXPECT_EQ(h.map_.numKeyFrames(), 2u);
  EXPECT_EQ(h.keyframes_[0]->covisibility.at(h.keyframes_[1].get()), 2);
}

TEST(ErasePoint, UnlinksItFromEveryKeyFrame) {
  HandMap h(3);
  h.addChain(2);
  h.see(0, 0, 3);
  h.see(1, 0, 3);
  h.map_.erasePoint(h.points_[1]);
  EXPECT_TRUE(h.points_[1]->bad);
  EXPECT_EQ(h.keyframes_[0]->map_points[1], nullptr);
  EXPECT_EQ(h.keyframes_[0]->covisibility.at(h.keyframes_[1].get()), 2);
  expectConsistent(h.map_);
}

// A keyframe can hold one point at two keypoints (its frame matched it twice): unlinking one
// leaves the other linked and counted, so that erasing the point later unlinks it too.
TEST(RemoveObservation, LeavesTheOtherKeypointOfAPointSeenTwice) {
  HandMap h(3);
  h.addChain(2);
  h.see(1, 0, 3);
  KeyFrame& twice = *h.keyframes_[0];
  h.map_.addObservation(twice, 0, h.points_[2]);
  h.map_.addObservation(twice, 2, h.points_[2]);
  h.map_.removeObservation(twice, 0);
  EXPECT_EQ(twice.map_points[0], nullptr);
  ASSERT_EQ(twice.map_points[2], h.points_[2]);
  EXPECT_TRUE(h.points_[2]->seenBy(&twice));
  EXPECT_EQ(twice.covisibility.at(h.keyframes_[1].get()), 1);
  h.map_.erasePoint(h.points_[2]);
  EXPECT_EQ(twice.map_points[2], nullptr);  // no link left to an erased point
}

// What left the container is named once, for the MapUpdate that tells mapping_node.
TEST(RemoveBadPoints, NamesTheRemovedPointsOnce) {
  HandMap h(4);
  h.addChain(2);
  h.see(0, 0, 4);
  h.see(1, 0, 4);
  h.map_.erasePoint(h.points_[1]);
  h.map_.erasePoint(h.points_[3]);
  EXPECT_EQ(h.map_.removeBadLandmarks(), 2u);
  EXPECT_EQ(h.map_.takeRemovedPoints(), (std::vector<long>{h.points_[1]->id, h.points_[3]->id}));
  EXPECT_TRUE(h.map_.takeRemovedPoints().empty());
  const auto kept = h.map_.mapPoints();
  ASSERT_EQ(kept.size(), 2u);
  EXPECT_EQ(kept[0], h.points_[0]);  // the kept ones in their order
  EXPECT_EQ(kept[1], h.points_[2]);
}

// A line seen by two keyframes leaves the map when the second of them is erased, and is named
// once, like a point.
TEST(RemoveBadLandmarks, ALineGoesWithTheLastKeyFrameThatSawIt) {
  HandMap h(4);
  h.addChain(4);
  for (int k = 0; k < 4; ++k) h.see(k, 0, 4);  // keyframes 1 and 2 stay erasable
  const auto line = h.map_.createMapLine({0, 0, 3}, {1, 0, 3}, cv::Mat(), 1);
  const auto kept_line = h.map_.createMapLine({0, 1, 3}, {1, 1, 3}, cv::Mat(), 0);
  for (int k : {1, 2}) h.keyframes_[k]->map_lines[0] = line;
  line->observations = 2;
  h.keyframes_[0]->map_lines[0] = kept_line;
  kept_line->observations = 1;
  ASSERT_TRUE(h.map_.eraseKeyFrame(*h.keyframes_[1], 2));
  EXPECT_EQ(h.map_.removeBadLandmarks(), 0u);  // keyframe 2 still sees it
  ASSERT_TRUE(h.map_.eraseKeyFrame(*h.keyframes_[2], 2));
  EXPECT_TRUE(line->bad);
  EXPECT_EQ(h.map_.removeBadLandmarks(), 1u);
  EXPECT_EQ(h.map_.takeRemovedLines(), std::vector<long>{line->id});
  EXPECT_TRUE(h.map_.takeRemovedLines().empty());
  EXPECT_TRUE(h.map_.takeRemovedPoints().empty());
  const auto lines = h.map_.mapLines();
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_EQ(lines[0], kept_line);
}

// Five keyframes: points 0-9 seen by all, 10-14 by keyframes 0 and 1 only, 15-19 by 3 and 4
// only. Keyframe 2 sees only 0-9, each by four others: redundant. Keyframes 1 and 3 have a
// third of their points seen by one other keyframe: kept.
class RedundantKeyFrame : public testing::Test {
 protected:
  void SetUp() override {
    h_.addChain(5);
    for (int k = 0; k < 5; ++k) h_.see(k, 0, 10, k == 2 ? coarse_level_ : 0);
    h_.see(0, 10, 15);
    h_.see(1, 10, 15);
    h_.see(3, 15, 20);
    h_.see(4, 15, 20);
  }

  int coarse_level_ = 1;  // keyframe 2 sees a level coarser than the others: they count
  HandMap h_{20};
};

TEST_F(RedundantKeyFrame, OnlyTheRedundantKeyFrameIsErased) {
  const KeyFrameCuller culler;
  EXPECT_TRUE(culler.redundant(*h_.keyframes_[2]));
  EXPECT_FALSE(culler.redundant(*h_.keyframes_[1]));
  EXPECT_FALSE(culler.redundant(*h_.keyframes_[3]));
  EXPECT_EQ(culler.cull(h_.map_, *h_.keyframes_[4], {}), std::vector<long>{2});
  EXPECT_EQ(h_.map_.numKeyFrames(), 4u);
  EXPECT_EQ(h_.keyframes_[3]->parent, h_.keyframes_[1].get());
  for (int i = 0; i < 10; ++i) EXPECT_EQ(h_.points_[i]->observations(), 4);
  expectConsistent(h_.map_);
}

TEST_F(RedundantKeyFrame, KeptKeyFramesAreLeft) {
  EXPECT_TRUE(KeyFrameCuller().cull(h_.map_, *h_.keyframes_[4], {2}).empty());
  EXPECT_EQ(h_.map_.numKeyFrames(), 5u);
}

TEST_F(RedundantKeyFrame, TheNewestAndTheFirstAreNeverErased) {
  // Keyframe 0 and 4 each see everything keyframe 2 does, and more that only one other sees.
  KeyFrameCullerOptions lenient;
  lenient.redundancy = 0.5;
  const std::vector<long> erased = KeyFrameCuller(lenient).cull(h_.map_, *h_.keyframes_[4], {});
  EXPECT_EQ(std::count(erased.begin(), erased.end(), 0L), 0);
  EXPECT_EQ(std::count(erased.begin(), erased.end(), 4L), 0);
  expectConsistent(h_.map_);
}

TEST(KeyFrameCullerScale, CoarserViewsDoNotReplaceAFinerOne) {
  // Keyframe 2 sees points 0-9 at level 0; the others only two levels coarser.
  HandMap h(10);
  h.addChain(5);
  for (int k = 0; k < 5; ++k) h.see(k, 0, 10, k == 2 ? 0 : 2);
  EXPECT_FALSE(KeyFrameCuller().redundant(*h.keyframes_[2]));
  EXPECT_TRUE(KeyFrameCuller().redundant(*h.keyframes_[1]));  // level 2, others at 0 and 2
}

TEST(MapPointCuller, RetiresPointsRarelyFoundWhereTheyWereInView) {
  HandMap h(3);
  h.addChain(2);
  h.see(0, 0, 3);
  h.see(1, 0, 3);
  h.points_[0]->visible = 20;  // found 4 of 20: 0.2
  h.points_[0]->found = 4;
  h.points_[1]->visible = 20;  // 0.3
  h.points_[1]->found = 6;
  h.points_[2]->visible = 5;  // never found, but seen too few times to judge
  MapPointCuller culler;
  EXPECT_EQ(culler.cull(h.map_, *h.keyframes_[1], {h.keyframes_[0].get()}), 1);
  EXPECT_TRUE(h.points_[0]->bad);
  EXPECT_EQ(h.keyframes_[0]->map_points[0], nullptr);
  EXPECT_FALSE(h.points_[1]->bad);
  EXPECT_FALSE(h.points_[2]->bad);
  expectConsistent(h.map_);
}

TEST(MapPointCuller, RetiresNewPointsNoLaterKeyFrameConfirmed) {
  // Keyframe 1 creates points 0-3; keyframe 2 sees 0-1 again, keyframe 3 sees 1 again.
  HandMap h(4);
  h.addChain(4);
  for (const auto& p : h.points_) p->first_keyframe_id = 1;
  h.see(1, 0, 4);
  MapPointCuller culler;
  EXPECT_EQ(culler.cull(h.map_, *h.keyframes_[1], {}), 0);
  h.see(2, 0, 2);
  EXPECT_EQ(culler.cull(h.map_, *h.keyframes_[2], {}), 0);  // one keyframe later: too early
  h.see(3, 1, 2);
  EXPECT_EQ(culler.cull(h.map_, *h.keyframes_[3], {}), 2);  // two later: 2 and 3 are alone
  EXPECT_FALSE(h.points_[0]->bad);
  EXPECT_FALSE(h.points_[1]->bad);
  EXPECT_TRUE(h.points_[2]->bad);
  EXPECT_TRUE(h.points_[3]->bad);
  expectConsistent(h.map_);
}

}  // namespace
}  // namespace ply_slam
