// mapping_node: see ply_slam::MappingNode (include/ply_slam/ros/mapping_node.h).
#include <ros/ros.h>

#include "ply_slam/ros/mapping_node.h"

int main(int argc, char** argv) {
  ros::init(argc, argv, "mapping_node");
  // Held here, not by the node alone: when its constructor throws, the last NodeHandle going
  // would shut ROS down and its logging with it, and the node would die without a word.
  ros::NodeHandle nh, pnh("~");
  try {
    ply_slam::MappingNode node(nh, pnh);
    ros::spin();
  } catch (const std::exception& e) {
    ROS_FATAL_STREAM("mapping_node: " << e.what());
    return 1;
  }
  return 0;
}
