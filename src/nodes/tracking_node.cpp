// tracking_node: see ply_slam::TrackingNode (include/ply_slam/ros/tracking_node.h).
#include <ros/ros.h>

#include "ply_slam/ros/tracking_node.h"

int main(int argc, char** argv) {
  ros::init(argc, argv, "tracking_node");
  try {
    ply_slam::TrackingNode node(ros::NodeHandle(), ros::NodeHandle("~"));
    ros::spin();
  } catch (const std::exception& e) {
    ROS_FATAL_STREAM("tracking_node: " << e.what());
    return 1;
  }
  return 0;
}
