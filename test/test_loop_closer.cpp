// LoopCloser's locking: the loop query and its geometric check read nothing of the map, so they
// run while another thread (the tracker) holds the map's lock and asks the place database.
#include <gtest/gtest.h>

#include <chrono>
#include <future>
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

TEST(LoopCloser, QueriesTheDatabaseWhileTheTrackerHoldsTheMap) {
  PLY_SLAM_REQUIRE_VOCABULARY(vocabularyPath("", DescriptorKind::kOrb));
  PLY_SLAM_REQUIRE_VOCABULARY(vocabularyPath("", DescriptorKind::kLbd));
  const PinholeCamera camera = test::loopTestCamera();
  MapperOptions options;
  options.loop.enabled = true;
  Map map;
  const LandmarkFuser fuser(camera, options.orb, options.local);
  LoopCloser closer(LoopDetector::fromOptions(camera, options.loop), camera, options, fuser, map);
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

}  // namespace
}  // namespace ply_slam
