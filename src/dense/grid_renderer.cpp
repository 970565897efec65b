#include "ply_slam/dense/grid_renderer.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

#include "ply_slam/dense/grid_map_files.h"
#include "ply_slam/dense/map_drawing.h"

namespace ply_slam {

GridRenderer::GridRenderer(int max_map_px) : max_map_px_(max_map_px) {
  if (max_map_px < 100) throw std::invalid_argument("GridRenderer: max_map_px must be >= 100");
}

cv::Mat GridRenderer::render(const OccupancyGrid& grid, const Trajectory& trajectory,
                             const std::string& title) const {
  const int cells = std::max({grid.width(), grid.height(), 1});
  const int px_per_cell = std::clamp(max_map_px_ / cells, 1, 8);
  cv::Mat cells_image = grid.width() > 0 ? gridMapImage(grid) : cv::Mat(1, 1, CV_8UC1, 205);
  cv::Mat map;
  cv::resize(cells_image, map, cv::Size(), px_per_cell, px_per_cell, cv::INTER_NEAREST);
  cv::cvtColor(map, map, cv::COLOR_GRAY2BGR);

  // The path on the floor, in image pixels (rows run against the grid's y).
  const Eigen::Isometry3d T_floor_world = grid.floor().T_world_floor.inverse();
  const double px_per_m = px_per_cell / grid.resolution();
  std::vector<cv::Point> path;
  for (const auto& pose : trajectory) {
    const Eigen::Vector3d p = T_floor_world * pose.T_wc.translation();
    path.emplace_back(std::lround((p.x() - grid.origin().x()) * px_per_m),
                      std::lround(map.rows - (p.y() - grid.origin().y()) * px_per_m));
  }
  drawTrajectory(map, path);
  drawScaleBar(map, px_per_m);

  const int title_h = 30;
  cv::Mat image(std::max(map.rows, 100) + title_h, std::max(map.cols, 400), CV_8UC3,
                cv::Scalar(255, 255, 255));
  map.copyTo(image(cv::Rect(0, title_h, map.cols, map.rows)));
  cv::putText(image, title, cv::Point(8, 21), cv::FONT_HERSHEY_SIMPLEX, 0.55, cv::Scalar(0, 0, 0),
              1, cv::LINE_AA);
  return image;
}

void GridRenderer::write(const std::string& png_path, const OccupancyGrid& grid,
                         const Trajectory& trajectory, const std::string& title) const {
  if (!cv::imwrite(png_path, render(grid, trajectory, title)))
    throw std::runtime_error("cannot write " + png_path);
}

}  // namespace ply_slam
