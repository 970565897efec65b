#include "ply_slam/ros/mapper_update_feed.h"

#include <std_msgs/UInt64.h>

#include "ply_slam/ros/conversions.h"

namespace ply_slam {

MapperUpdateFeed::MapperUpdateFeed(ros::NodeHandle nh, ros::NodeHandle pnh,
                                   const std::string& topic, BadInputLog& bad_input,
                                   std::function<void()> woken)
    : bad_input_(bad_input), woken_(std::move(woken)), last_arrival_(ros::WallTime::now()) {
  update_sub_ = nh.subscribe(topic, 100, &MapperUpdateFeed::onUpdate, this);
  wanted_pub_ = pnh.advertise<std_msgs::UInt64>("updates_wanted", 10);
  check_timer_ =
      nh.createWallTimer(ros::WallDuration(0.25), [this](const ros::WallTimerEvent&) { check(); });
}

bool MapperUpdateFeed::ready() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return queue_.ready();
}

std::vector<MapUpdate> MapperUpdateFeed::takeReady() {
  std::lock_guard<std::mutex> lock(mutex_);
  return queue_.takeReady();
}

void MapperUpdateFeed::restartAt(uint64_t next) {
  std::lock_guard<std::mutex> lock(mutex_);
  queue_.restartAt(next);
}

// One that comes early waits until those before it come again.
void MapperUpdateFeed::onUpdate(const ply_slam::MapUpdateMsgConstPtr& msg) {
  MapUpdate update;
  try {
    update = fromMsg(*msg);
  } catch (const std::exception& e) {
    bad_input_.report("map_update", e.what());
    return;
  }
  last_arrival_ = ros::WallTime::now();
  quiet_asked_ = false;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    // False: sent again and here already, or made before a handover (that side started anew).
    if (!queue_.push(msg->sequence, std::move(update))) return;
  }
  woken_();
  check();
}

void MapperUpdateFeed::check() {
  std::optional<uint64_t> missing;
  uint64_t next = 0;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    missing = queue_.firstMissing();
    next = queue_.next();
  }
  const ros::WallTime now = ros::WallTime::now();
  if (!missing) {
    hole_.reset();
    if (quiet_asked_ || (now - last_arrival_).toSec() < kQuiet) return;
    quiet_asked_ = true;
    ask(next);  // usually none went by: nothing comes
    return;
  }
  if (hole_ != missing) {  // a new gap
    hole_ = missing;
    hole_seen_at_ = now;
    ROS_WARN_STREAM("tracking_node: map update " << *missing << " from the mapping side is "
                                                 << "missing; asked for it again");
    ask(*missing);
    return;
  }
  if ((now - hole_seen_at_).toSec() < kGiveUp) {
    if ((now - asked_at_).toSec() >= kAskAgain) ask(*missing);
    return;
  }
  uint64_t lost = 0;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    lost = queue_.skipMissing();
  }
  lost_ += lost;
  hole_.reset();
  woken_();
  ROS_ERROR_STREAM("tracking_node: map updates " << *missing << " to " << *missing + lost - 1
                                                 << " from the mapping side never came; the "
                                                    "tracker's copy of the map goes on without");
}

void MapperUpdateFeed::ask(uint64_t from) {
  std_msgs::UInt64 msg;
  msg.data = from;
  wanted_pub_.publish(msg);
  asked_at_ = ros::WallTime::now();
  ++asked_;
}

}  // namespace ply_slam
