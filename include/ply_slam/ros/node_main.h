#pragma once

#include <ros/node_handle.h>

#include <functional>
#include <string>

namespace ply_slam {

// A node's main: ros::init as `name`, then `run` with the public and the private NodeHandle
// (run builds the node and spins). An exception is logged as "NAME: what" (ROS_FATAL) and gives
// exit code 1. The handles are held here, not by the node alone: when the node's constructor
// throws, the last NodeHandle going would shut ROS down and its logging with it, and the node
// would die without a word.
int runNode(int argc, char** argv, const std::string& name,
            const std::function<void(ros::NodeHandle& nh, ros::NodeHandle& pnh)>& run);

}  // namespace ply_slam
