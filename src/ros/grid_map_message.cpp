#include "ply_slam/ros/grid_map_message.h"

#include "ply_slam/ros/conversions.h"

namespace ply_slam {

nav_msgs::OccupancyGrid toGridMsg(const OccupancyGrid& grid, const Eigen::Isometry3d& T_frame_floor,
                                  const std_msgs::Header& header) {
  nav_msgs::OccupancyGrid msg;
  msg.header = header;
  msg.info.map_load_time = header.stamp;
  msg.info.resolution = static_cast<float>(grid.resolution());
  msg.info.width = static_cast<std::uint32_t>(grid.width());
  msg.info.height = static_cast<std::uint32_t>(grid.height());
  msg.info.origin = toPoseMsg(grid.corner(T_frame_floor));
  msg.data = grid.cells();
  return msg;
}

}  // namespace ply_slam
