// LoopCloser's locking: the loop query and its geometric check read nothing of the map, so they
// run while another thread (the tracker) holds the map's lock and asks the place database.
#include <gtest/gtest.h>

#include <chrono>
#include <future>
#include <memory>
#include <random>

#include "default_vocabularies.h"
#include "loop_test_data.h"
#include "ply_slam/mapping/loop_closer.h"

namespace ply_slam {
namespace {

// A keyframe as the database takes it: `descriptors` at random pixels, 2 m away.
LoopKeyFrame describedKeyFrame(long id, double stamp, const cv::Mat& descriptors,
                               std::mt19937& rng) {
  LoopKeyFrame kf;
  kf.id = id;
  kf.stamp = stamp;
  kf.orb_descriptors = descriptors;
  std::uniform_real_distribution<double> u(0.0, 640.0), v(0.0, 480.0);
  for (int r = 0; r < descriptors.rows; ++r) {
    kf.keypoints.emplace_back(u(rng), v(rng));
    kf.depth.push_back(2.0f);
  }
  return kf;
}

KeyFrame mapKeyFrame(long id, double stamp) {
  KeyFrame kf;
  kf.id = id;
  kf.stamp = stamp;
  return kf;
}

// A place database over an empty map, with the default vocabularies.
class LoopCloserTest : public ::testing::Test {
 protected:
  void SetUp() override {
    PLY_SLAM_REQUIRE_VOCABULARY(vocabularyPath("", DescriptorKind::kOrb));
    PLY_SLAM_REQUIRE_VOCABULARY(vocabularyPath("", DescriptorKind::kLbd));
    options_.loop.enabled = true;
    closer_ = std::make_unique<LoopCloser>(LoopDetector::fromOptions(camera_, options_.loop),
                                           camera_, options_, fuser_, map_);
  }

  const PinholeCamera camera_ = test::loopTestCamera();
  MapperOptions options_;
  Map map_;
  const LandmarkFuser fuser_{camera_, options_.orb, options_.local};
  std::unique_ptr<LoopCloser> closer_;
};

TEST_F(LoopCloserTest, QueriesTheDatabaseWhileTheTrackerHoldsTheMap) {
  Map& map = map_;
  LoopCloser& closer = *closer_;
  std::mt19937 rng(7);
  const cv::Mat seen = test::randomDescriptors(400, rng);
  const KeyFrame first = mapKeyFrame(0, 0.0), again = mapKeyFrame(1, 20.0);
  {
    std::lock_guard<std::mutex> lock(map.updateMutex());  // as the mapping side adds them
    EXPECT_TRUE(closer.addKeyFrame(first, describedKeyFrame(0, 0.0, seen, rng)));
    EXPECT_TRUE(
        closer.addKeyFrame(again, describedKeyFrame(1, 20.0, test::noisyCopy(seen, 8, rng), rng)));
  }
  // The tracker's thread holds the map for its frame and relocalises through the database while
  // the mapping side queries it: the query must not need the map's lock.
  std::unique_lock<std::mutex> tracker(map.updateMutex());
  auto query = std::async(std::launch::async, [&] { return closer.detect(1); });
  std::vector<long> places;
  for (int i = 0; i < 20; ++i) places = closer.recognise(seen, 2);
  const std::future_status status = query.wait_for(std::chrono::seconds(60));
  tracker.unlock();  // a query stuck on the lock ends, and the test with it
  ASSERT_EQ(status, std::future_status::ready) << "the loop query waited for the map's lock";
  // One query is no loop yet (consistency over loop.consistency queries).
  EXPECT_FALSE(query.get().has_value());
  ASSERT_FALSE(places.empty());
  EXPECT_EQ(places.front(), 0);
}

// With the mapping thread the tracker makes keyframes the mapping side has not added to the
// database yet; a loop's fusion links them to the keyframes it syncs (a ring run stopped with
// "LoopDetector: no keyframe 366").
TEST_F(LoopCloserTest, SyncsCovisibilityWithKeyFramesTheDatabaseHasNotGot) {
  LoopCloser& closer = *closer_;
  std::mt19937 rng(3);
  KeyFrame added = mapKeyFrame(0, 0.0), newer = mapKeyFrame(1, 0.5);
  EXPECT_TRUE(
      closer.addKeyFrame(added, describedKeyFrame(0, 0.0, test::randomDescriptors(100, rng), rng)));
  added.covisibility[&newer] = 40;
  newer.covisibility[&added] = 40;
  EXPECT_NO_THROW(closer.syncCovisibility(added));
  EXPECT_NO_THROW(closer.syncCovisibility(newer));
}

}  // namespace
}  // namespace ply_slam
