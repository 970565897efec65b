// InOrderQueue: numbered messages given out in their order, whatever order they came in; what
// a receiver asks for again, and what it gives up.
#include <gtest/gtest.h>

#include <string>

#include "ply_slam/common/in_order_queue.h"

namespace ply_slam {
namespace {

TEST(InOrderQueue, GivesOutInOrderAndWaitsForWhatIsMissing) {
  InOrderQueue<std::string> queue;
  EXPECT_FALSE(queue.firstMissing());
  EXPECT_TRUE(queue.push(0, "a"));
  EXPECT_TRUE(queue.push(2, "c"));     // 1 lost on the way
  EXPECT_FALSE(queue.firstMissing());  // 0 is here: nothing missing yet
  EXPECT_TRUE(queue.ready());
  EXPECT_EQ(queue.takeReady(), std::vector<std::string>{"a"});
  EXPECT_FALSE(queue.ready());
  ASSERT_TRUE(queue.firstMissing());
  EXPECT_EQ(*queue.firstMissing(), 1u);
  EXPECT_TRUE(queue.takeReady().empty());  // 2 waits for 1
  EXPECT_TRUE(queue.push(3, "d"));
  EXPECT_FALSE(queue.push(3, "d again"));  // a repeat of one waiting
  EXPECT_TRUE(queue.push(1, "b"));         // sent again
  EXPECT_FALSE(queue.firstMissing());
  EXPECT_EQ(queue.takeReady(), (std::vector<std::string>{"b", "c", "d"}));
  EXPECT_FALSE(queue.push(2, "c again"));  // a repeat of one given out
  EXPECT_EQ(queue.next(), 4u);
  EXPECT_EQ(queue.waiting(), 0u);
}

TEST(InOrderQueue, GivesUpWhatNeverComes) {
  InOrderQueue<int> queue;
  queue.push(3, 30);
  queue.push(5, 50);
  EXPECT_EQ(*queue.firstMissing(), 0u);
  EXPECT_EQ(queue.skipMissing(), 3u);  // 0, 1, 2 given up
  EXPECT_EQ(queue.takeReady(), std::vector<int>{30});
  EXPECT_EQ(*queue.firstMissing(), 4u);
  EXPECT_EQ(queue.skipMissing(), 1u);
  EXPECT_EQ(queue.takeReady(), std::vector<int>{50});
  EXPECT_EQ(queue.skipMissing(), 0u);  // nothing waiting: nothing to give up
  EXPECT_EQ(queue.next(), 6u);
}

TEST(InOrderQueue, ARestartDropsWhatCameBefore) {
  InOrderQueue<int> queue;
  queue.push(0, 0);
  queue.push(2, 2);
  queue.push(7, 7);
  queue.restartAt(6);  // the sender started anew at 6
  EXPECT_EQ(queue.next(), 6u);
  EXPECT_EQ(queue.waiting(), 1u);
  EXPECT_FALSE(queue.push(5, 5));
  EXPECT_EQ(*queue.firstMissing(), 6u);
  queue.push(6, 6);
  EXPECT_EQ(queue.takeReady(), (std::vector<int>{6, 7}));
  queue.push(9, 9);
  queue.restartAt(0);  // a restarted sender numbers from 0 again: 9 was the old one's
  EXPECT_EQ(queue.next(), 0u);
  EXPECT_EQ(queue.waiting(), 0u);
  EXPECT_TRUE(queue.push(0, 100));
  EXPECT_EQ(queue.takeReady(), std::vector<int>{100});
}

}  // namespace
}  // namespace ply_slam
