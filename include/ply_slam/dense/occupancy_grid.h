#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <string>
#include <vector>

namespace ply_slam {

// Where the floor is in the SLAM world: the floor frame has z up, z = 0 on the floor, its
// origin under the first camera and x along that camera's view (a robot's base_footprint at
// the start, as REP 105 places `map`).
struct FloorFrame {
  Eigen::Isometry3d T_world_floor = Eigen::Isometry3d::Identity();
  std::string method = "given";  // "plane": fitted to the octree; "lowest": fallback; "given"
  size_t support = 0;            // occupied voxels on the fitted plane
};

// A 2D grid on the floor: cell (i, j) covers floor-frame x in [origin.x + i res, + res) and y
// likewise; cells row by row from the lowest y, as nav_msgs/OccupancyGrid stores them.
class OccupancyGrid {
 public:
  static constexpr std::int8_t kUnknown = -1, kFree = 0, kOccupied = 100;  // nav_msgs values

  OccupancyGrid() = default;
  OccupancyGrid(int width, int height, double resolution, const Eigen::Vector2d& origin,
                FloorFrame floor);

  int width() const { return width_; }
  int height() const { return height_; }
  double resolution() const { return resolution_; }
  const Eigen::Vector2d& origin() const { return origin_; }  // floor xy of cell (0, 0)'s corner
  const FloorFrame& floor() const { return floor_; }
  // Cell (0, 0)'s corner in the frame the floor frame lies at T_frame_floor in: map_server's and
  // nav_msgs' grid origin.
  Eigen::Isometry3d corner(const Eigen::Isometry3d& T_frame_floor) const {
    return T_frame_floor * Eigen::Translation3d(origin_.x(), origin_.y(), 0.0);
  }
  const std::vector<std::int8_t>& cells() const { return cells_; }

  std::int8_t at(int i, int j) const { return cells_[index(i, j)]; }
  void set(int i, int j, std::int8_t state) { cells_[index(i, j)] = state; }
  // The cell holding floor-frame point xy; false outside the grid.
  bool cellOf(const Eigen::Vector2d& xy, int* i, int* j) const;
  Eigen::Vector2d cellCentre(int i, int j) const;  // floor frame
  size_t count(std::int8_t state) const;

 private:
  size_t index(int i, int j) const { return static_cast<size_t>(j) * width_ + i; }

  int width_ = 0, height_ = 0;
  double resolution_ = 0.05;
  Eigen::Vector2d origin_ = Eigen::Vector2d::Zero();
  FloorFrame floor_;
  std::vector<std::int8_t> cells_;
};

}  // namespace ply_slam
