#pragma once

#include <ply_slam/MapUpdateMsg.h>
#include <ros/ros.h>

#include <atomic>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "ply_slam/common/in_order_queue.h"
#include "ply_slam/map/key_frame_packet.h"
#include "ply_slam/ros/bad_input_log.h"

namespace ply_slam {

// The mapping side's updates as a tracker apart (~mapping_apart) gets them from mapping_node:
// strictly in the order they were made, each building on the one before. One missing (a gap, or
// kQuiet without any: a last update lost shows no gap) is asked for on ~updates_wanted (the first
// missing number), again every kAskAgain; after kGiveUp the feed goes on without it (logged,
// counted as lost). Updates numbered below where the sender (re)starts are dropped.
//
// Threads: the subscriber and the check timer run on the spinner; ready, takeReady and restartAt
// on any thread (the feed locks itself). `woken` is called on the spinner, with no lock of the
// feed's held, when updates became ready.
class MapperUpdateFeed {
 public:
  MapperUpdateFeed(ros::NodeHandle nh, ros::NodeHandle pnh, const std::string& topic,
                   BadInputLog& bad_input, std::function<void()> woken);

  bool ready() const;
  std::vector<MapUpdate> takeReady();  // those ready, in order
  // The sender numbers on from `next` (a handover, a restarted mapping_node): those before it are
  // not followed.
  void restartAt(uint64_t next);
  size_t asked() const { return asked_; }  // times ~updates_wanted went out
  size_t lost() const { return lost_; }    // updates given up on

 private:
  void onUpdate(const ply_slam::MapUpdateMsgConstPtr& msg);
  void check();  // on the timer and after each update
  void ask(uint64_t from);

  BadInputLog& bad_input_;
  std::function<void()> woken_;
  mutable std::mutex mutex_;       // guards queue_
  InOrderQueue<MapUpdate> queue_;  // under mutex_
  // check()'s state, spinner thread only.
  static constexpr double kAskAgain = 1.0, kGiveUp = 5.0, kQuiet = 2.0;  // s
  ros::WallTime last_arrival_, asked_at_, hole_seen_at_;
  std::optional<uint64_t> hole_;  // the first missing update when it was seen
  bool quiet_asked_ = false;
  std::atomic<size_t> asked_{0}, lost_{0};
  ros::Subscriber update_sub_;
  ros::Publisher wanted_pub_;
  ros::WallTimer check_timer_;
};

}  // namespace ply_slam
