#include "ply_slam/ros/node_main.h"

#include <ros/ros.h>

#include <exception>

namespace ply_slam {

int runNode(int argc, char** argv, const std::string& name,
            const std::function<void(ros::NodeHandle& nh, ros::NodeHandle& pnh)>& run) {
  ros::init(argc, argv, name);
  ros::NodeHandle nh, pnh("~");
  try {
    run(nh, pnh);
  } catch (const std::exception& e) {
    ROS_FATAL_STREAM(name << ": " << e.what());
    return 1;
  }
  return 0;
}

}  // namespace ply_slam
