#pragma once

#include <ros/node_handle.h>

#include <string>

#include "ply_slam/system/system_config.h"

namespace ply_slam {

// The SystemConfig under parameter `key` of `nh` (launch files load a config/*.yaml there with
// <rosparam command="load" ns="config"/> and may override any key), checked exactly like
// loadConfig: the parameter tree is turned back into a YAML document and goes through the same
// parser. Throws ConfigError naming the parameter and key.
SystemConfig configFromParams(const ros::NodeHandle& nh, const std::string& key = "config");

}  // namespace ply_slam
