#include "ply_slam/ros/node_params.h"

#include <stdexcept>

namespace ply_slam {

void badParam(const std::string& name, const std::string& why) {
  throw std::invalid_argument("~" + name + " " + why);
}

std::string frameParam(std::string frame) {
  while (!frame.empty() && frame.front() == '/') frame.erase(frame.begin());
  return frame;
}

}  // namespace ply_slam
