// mapping_node: see ply_slam::MappingNode (include/ply_slam/ros/mapping_node.h).
#include <ros/ros.h>

#include "ply_slam/ros/mapping_node.h"
#include "ply_slam/ros/node_main.h"

int main(int argc, char** argv) {
  return ply_slam::runNode(
      argc, argv, "mapping_node", [](ros::NodeHandle& nh, ros::NodeHandle& pnh) {
        ply_slam::MappingNodeOptions options = ply_slam::mappingNodeOptionsFromParams(pnh);
        ply_slam::MappingBackEnd back_end = ply_slam::MappingBackEnd::fromOptions(options);
        ply_slam::MappingNode node(nh, pnh, std::move(options), std::move(back_end));
        ros::spin();
      });
}
