#include "ply_slam/dense/occupancy_grid.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace ply_slam {

OccupancyGrid::OccupancyGrid(int width, int height, double resolution,
                             const Eigen::Vector2d& origin, FloorFrame floor)
    : width_(width),
      height_(height),
      resolution_(resolution),
      origin_(origin),
      floor_(std::move(floor)) {
  if (width < 0 || height < 0) throw std::invalid_argument("OccupancyGrid: negative size");
  if (!(resolution > 0.0)) throw std::invalid_argument("OccupancyGrid: resolution must be > 0");
  cells_.assign(static_cast<size_t>(width) * height, kUnknown);
}

bool OccupancyGrid::cellOf(const Eigen::Vector2d& xy, int* i, int* j) const {
  const Eigen::Vector2d cell = (xy - origin_) / resolution_;
  if (!(cell.x() >= 0.0 && cell.y() >= 0.0)) return false;
  *i = static_cast<int>(std::floor(cell.x()));
  *j = static_cast<int>(std::floor(cell.y()));
  return *i < width_ && *j < height_;
}

Eigen::Vector2d OccupancyGrid::cellCentre(int i, int j) const {
  return origin_ + resolution_ * Eigen::Vector2d(i + 0.5, j + 0.5);
}

size_t OccupancyGrid::count(std::int8_t state) const {
  return static_cast<size_t>(std::count(cells_.begin(), cells_.end(), state));
}

}  // namespace ply_slam
