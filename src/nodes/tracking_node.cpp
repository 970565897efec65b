// tracking_node: see ply_slam::TrackingNode (include/ply_slam/ros/tracking_node.h).
#include <ros/ros.h>

#include "ply_slam/ros/node_main.h"
#include "ply_slam/ros/tracking_node.h"

int main(int argc, char** argv) {
  return ply_slam::runNode(
      argc, argv, "tracking_node", [](ros::NodeHandle& nh, ros::NodeHandle& pnh) {
        ply_slam::TrackingNodeOptions options = ply_slam::trackingNodeOptionsFromParams(pnh);
        ply_slam::TrackingBackEnd back_end = ply_slam::TrackingBackEnd::fromOptions(options);
        ply_slam::TrackingNode node(nh, pnh, std::move(options), std::move(back_end));
        ros::spin();
      });
}
