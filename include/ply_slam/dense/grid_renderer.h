#pragma once

#include <opencv2/core.hpp>
#include <string>

#include "ply_slam/common/stamped_pose.h"
#include "ply_slam/dense/occupancy_grid.h"

namespace ply_slam {

// grid.png: the occupancy grid as map_server shows it (black occupied, white free, grey
// unknown), seen from above with the floor frame's x to the right, the camera path on the
// floor (the view grows to hold it), a 1 m scale bar and a title.
class GridRenderer {
 public:
  explicit GridRenderer(int max_map_px = 900);

  cv::Mat render(const OccupancyGrid& grid, const Trajectory& trajectory,
                 const std::string& title) const;
  // render() into a PNG; throws std::runtime_error when it cannot be written.
  void write(const std::string& png_path, const OccupancyGrid& grid, const Trajectory& trajectory,
             const std::string& title) const;

 private:
  int max_map_px_;
};

}  // namespace ply_slam
