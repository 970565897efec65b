#include "ply_slam/ros/bad_input_log.h"

#include <ros/console.h>
#include <ros/time.h>

namespace ply_slam {

void BadInputLog::report(const std::string& kind, const std::string& what) {
  std::lock_guard<std::mutex> lock(mutex_);
  Kind& k = kinds_[kind];
  ++k.count;
  const double now = ros::WallTime::now().toSec();
  if (now - k.last_log < period_s_) return;
  ROS_WARN_STREAM("skipped input ("
                  << kind << "): " << what << " [" << k.count - k.count_at_last_log
                  << " of this kind since the last warning, " << k.count << " in all]");
  k.last_log = now;
  k.count_at_last_log = k.count;
}

size_t BadInputLog::count(const std::string& kind) const {
  std::lock_guard<std::mutex> lock(mutex_);
  const auto it = kinds_.find(kind);
  return it == kinds_.end() ? 0 : it->second.count;
}

size_t BadInputLog::total() const {
  std::lock_guard<std::mutex> lock(mutex_);
  size_t n = 0;
  for (const auto& [name, k] : kinds_) n += k.count;
  return n;
}

std::string BadInputLog::summary() const {
  std::lock_guard<std::mutex> lock(mutex_);
  std::string out;
  for (const auto& [name, k] : kinds_)
    out += (out.empty() ? "" : " ") + name + "=" + std::to_string(k.count);
  return out;
}

}  // namespace ply_slam
