// MappingThread: the mapping side's queue. Jobs run in order on one thread, results wait for
// the tracking side, a failing job is reported and the next still runs, and nothing queued is
// dropped at the end.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <thread>

#include "ply_slam/system/mapping_thread.h"

namespace ply_slam {
namespace {

MappingJob jobFor(long frame_id) {
  MappingJob job;
  job.keyframe = std::make_shared<KeyFrame>();
  job.keyframe->frame_id = frame_id;
  return job;
}

MappedKeyFrame resultFor(const MappingJob& job) {
  MappedKeyFrame mapped;
  auto packet = std::make_shared<KeyFramePacket>();
  packet->frame_id = job.keyframe->frame_id;
  mapped.packet = packet;
  return mapped;
}

TEST(MappingThread, RunsJobsInOrderOnOneThreadBesideTheCaller) {
  const std::thread::id caller = std::this_thread::get_id();
  std::atomic<int> running{0}, most_at_once{0};
  std::atomic<bool> on_caller{false};
  MappingThread thread([&](const MappingJob& job) {
    most_at_once = std::max(most_at_once.load(), ++running);
    on_caller = on_caller || std::this_thread::get_id() == caller;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
    --running;
    return resultFor(job);
  });
  for (long i = 0; i < 20; ++i) thread.push(jobFor(i));
  thread.waitIdle();
  const std::vector<MappedKeyFrame> finished = thread.takeFinished();
  ASSERT_EQ(finished.size(), 20u);
  for (long i = 0; i < 20; ++i) EXPECT_EQ(finished[i].packet->frame_id, i);
  EXPECT_EQ(most_at_once, 1);
  EXPECT_FALSE(on_caller);
  EXPECT_TRUE(thread.takeFinished().empty());  // taken once
  EXPECT_GE(thread.longestQueue(), 1u);
}

TEST(MappingThread, AFailedJobIsReportedAndTheNextStillRuns) {
  MappingThread thread([](const MappingJob& job) {
    if (job.keyframe->frame_id == 1) throw std::runtime_error("keyframe 1 broke");
    return resultFor(job);
  });
  for (long i = 0; i < 3; ++i) thread.push(jobFor(i));
  thread.waitIdle();
  try {
    thread.takeFinished();
    FAIL() << "the failure was not reported";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("keyframe 1 broke"), std::string::npos) << e.what();
  }
  const std::vector<MappedKeyFrame> finished = thread.takeFinished();
  ASSERT_EQ(finished.size(), 2u);
  EXPECT_EQ(finished[0].packet->frame_id, 0);
  EXPECT_EQ(finished[1].packet->frame_id, 2);
}

TEST(MappingThread, QueuedJobsRunBeforeItStops) {
  std::atomic<int> done{0};
  {
    MappingThread thread([&](const MappingJob& job) {
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
      ++done;
      return resultFor(job);
    });
    for (long i = 0; i < 10; ++i) thread.push(jobFor(i));
  }
  EXPECT_EQ(done, 10);
}

}  // namespace
}  // namespace ply_slam
