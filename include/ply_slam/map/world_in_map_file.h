#pragma once

#include <Eigen/Geometry>
#include <optional>
#include <string>

namespace ply_slam {

// Where the SLAM world lies in the map frame a robot navigates in (mapping_node: with odometry,
// the camera's odom pose at the first tracked frame; else ~world_in_map), saved beside a map so
// that a robot that loads the map another day publishes map -> odom in the same map frame.
// One line: x y z (m) qx qy qz qw.
class WorldInMapFile {
 public:
  static constexpr const char* kName = "world_in_map.txt";

  // Whole or not at all (AtomicFile); throws std::runtime_error naming the file.
  static void write(const std::string& path, const Eigen::Isometry3d& T_map_world);
  // Nothing when there is no such file (a map saved offline, whose world is its map frame);
  // throws std::runtime_error naming the file when it cannot be read or is not one finite pose.
  static std::optional<Eigen::Isometry3d> read(const std::string& path);
};

}  // namespace ply_slam
