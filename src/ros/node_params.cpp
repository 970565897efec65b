#include "ply_slam/ros/node_params.h"

#include <stdexcept>

namespace ply_slam {

void badParam(const std::string& name, const std::string& why) {
  throw std::invalid_argument("~" + name + " " + why);
}

void readPeriod(const ros::NodeHandle& pnh, const std::string& name, double* seconds) {
  readParam(pnh, name, seconds);
  if (!(*seconds > 0.0)) badParam(name, "must be > 0 s");
}

std::string frameParam(std::string frame) {
  while (!frame.empty() && frame.front() == '/') frame.erase(frame.begin());
  return frame;
}

}  // namespace ply_slam
