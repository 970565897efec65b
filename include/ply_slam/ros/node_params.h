#pragma once

#include <ros/node_handle.h>

#include <string>

namespace ply_slam {

// A node's private parameter `name` into `value`. What `value` holds is the fallback for a node
// started without its launch file: the options structs state each one there, once; the launch
// files state the defaults users see.
template <typename T>
void readParam(const ros::NodeHandle& pnh, const std::string& name, T* value) {
  const T fallback = *value;
  pnh.param(name, *value, fallback);
}

// A parameter no node can run with: throws std::invalid_argument "~NAME WHY", the one way both
// nodes name a bad parameter (the main logs it and exits 1).
[[noreturn]] void badParam(const std::string& name, const std::string& why);

// A period parameter (s): throws as badParam unless it is > 0.
void readPeriod(const ros::NodeHandle& pnh, const std::string& name, double* seconds);

// `frame` without leading slashes (tf2 refuses them).
std::string frameParam(std::string frame);

}  // namespace ply_slam
