#include "ply_slam/dense/grid_renderer.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

#include "ply_slam/dense/grid_map_files.h"
#include "ply_slam/dense/map_drawing.h"
#include "ply_slam/io/image_file.h"

namespace ply_slam {

GridRenderer::GridRenderer(int max_map_px) : max_map_px_(max_map_px) {
  if (max_map_px < 100) throw std::invalid_argument("GridRenderer: max_map_px must be >= 100");
}

cv::Mat GridRenderer::render(const OccupancyGrid& grid, const Trajectory& trajectory,
                             const std::string& title) const {
  // What is drawn, in floor-frame metres: the grid and the camera path on the floor, with a
  // margin; outside the grid is unknown.
  const Eigen::Isometry3d T_floor_world = grid.floor().T_world_floor.inverse();
  std::vector<Eigen::Vector2d> path_xy;
  for (const auto& pose : trajectory)
    path_xy.push_back((T_floor_world * pose.T_wc.translation()).head<2>());
  const double res = grid.resolution();
  Eigen::Vector2d lo = grid.origin(),
                  hi = grid.origin() + res * Eigen::Vector2d(grid.width(), grid.height());
  for (const auto& p : path_xy) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  lo -= Eigen::Vector2d::Constant(0.3);
  hi += Eigen::Vector2d::Constant(0.3);
  const double extent = std::max(hi.x() - lo.x(), hi.y() - lo.y());
  const int px_per_cell = std::clamp(static_cast<int>(max_map_px_ * res / extent), 1, 8);
  const double px_per_m = px_per_cell / res;
  const cv::Size size(static_cast<int>(std::ceil((hi.x() - lo.x()) * px_per_m)),
                      static_cast<int>(std::ceil((hi.y() - lo.y()) * px_per_m)));
  // Image rows run against the floor's y.
  auto toPixel = [&](const Eigen::Vector2d& p) {
    return cv::Point(static_cast<int>(std::lround((p.x() - lo.x()) * px_per_m)),
                     static_cast<int>(std::lround((hi.y() - p.y()) * px_per_m)));
  };

  cv::Mat map(size, CV_8UC3, cv::Scalar(205, 205, 205));
  if (grid.width() > 0) {
    cv::Mat cells;
    cv::resize(gridMapImage(grid), cells, cv::Size(), px_per_cell, px_per_cell, cv::INTER_NEAREST);
    cv::cvtColor(cells, cells, cv::COLOR_GRAY2BGR);
    const cv::Point corner = toPixel(grid.origin() + Eigen::Vector2d(0.0, res * grid.height()));
    const cv::Rect place = cv::Rect(corner, cells.size()) & cv::Rect(cv::Point(), size);
    cells(cv::Rect(place.tl() - corner, place.size())).copyTo(map(place));
  }
  std::vector<cv::Point> path;
  for (const auto& p : path_xy) path.push_back(toPixel(p));
  drawTrajectory(map, path);
  drawScaleBar(map, px_per_m);

  const int title_h = 30;
  int baseline = 0;
  const int title_w =
      cv::getTextSize(title, cv::FONT_HERSHEY_SIMPLEX, 0.55, 1, &baseline).width + 16;
  cv::Mat image(map.rows + title_h, std::max(map.cols, title_w), CV_8UC3,
                cv::Scalar(255, 255, 255));
  map.copyTo(image(cv::Rect(0, title_h, map.cols, map.rows)));
  cv::putText(image, title, cv::Point(8, 21), cv::FONT_HERSHEY_SIMPLEX, 0.55, cv::Scalar(0, 0, 0),
              1, cv::LINE_AA);
  return image;
}

void GridRenderer::write(const std::string& png_path, const OccupancyGrid& grid,
                         const Trajectory& trajectory, const std::string& title) const {
  writeImageFile(png_path, render(grid, trajectory, title));
}

}  // namespace ply_slam
