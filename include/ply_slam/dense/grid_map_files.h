#pragma once

#include <Eigen/Geometry>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "ply_slam/dense/occupancy_grid.h"

namespace ply_slam {

// The grid as map_server's image: 8UC1, 0 (black) occupied, 254 free, 205 unknown; the top
// row is the grid's highest y (map_server puts the image's bottom-left pixel at the origin).
cv::Mat gridMapImage(const OccupancyGrid& grid);

// Writes `folder`/map.pgm and map.yaml in map_server's format (image, resolution, origin
// [x, y, yaw], negate 0, occupied_thresh 0.65, free_thresh 0.196: map_saver's values, which
// read 0 as occupied, 254 as free and 205 as unknown). `T_frame_floor` places the grid's floor
// frame in the frame the map is for (e.g. `map`; identity: the floor frame itself); origin
// and yaw are taken from it, its tilt dropped (map_server's maps are flat). Returns the paths;
// throws std::runtime_error naming a file that cannot be written.
std::vector<std::string> writeGridMap(
    const std::string& folder, const OccupancyGrid& grid,
    const Eigen::Isometry3d& T_frame_floor = Eigen::Isometry3d::Identity());

}  // namespace ply_slam
