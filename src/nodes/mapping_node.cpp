// mapping_node: see ply_slam::MappingNode (include/ply_slam/ros/mapping_node.h).
#include <ros/ros.h>

#include "ply_slam/ros/mapping_node.h"

int main(int argc, char** argv) {
  ros::init(argc, argv, "mapping_node");
  try {
    ply_slam::MappingNode node(ros::NodeHandle(), ros::NodeHandle("~"));
    ros::spin();
  } catch (const std::exception& e) {
    ROS_FATAL_STREAM("mapping_node: " << e.what());
    return 1;
  }
  return 0;
}
