#pragma once

#include <nav_msgs/OccupancyGrid.h>
#include <std_msgs/Header.h>

#include "ply_slam/dense/occupancy_grid.h"

namespace ply_slam {

// The grid as nav_msgs/OccupancyGrid in header.frame_id: `T_frame_floor` places the grid's
// floor frame there (its full pose goes into info.origin, so rviz shows the grid where the
// floor is; move_base's static layer reads only the origin's x and y). Cells as stored: -1, 0,
// 100, row by row from the origin.
nav_msgs::OccupancyGrid toGridMsg(const OccupancyGrid& grid, const Eigen::Isometry3d& T_frame_floor,
                                  const std_msgs::Header& header);

}  // namespace ply_slam
