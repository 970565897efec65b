#include "ply_slam/dense/occupancy_grid_options_yaml.h"

#include <vector>

namespace ply_slam {

OccupancyGridOptions readOccupancyGridOptions(ConfigSection section) {
  OccupancyGridOptions o;
  section.read("enabled", o.enabled);
  section.readInRange("resolution", o.resolution, 0.005, 1.0);
  section.readInRange("floor_clearance", o.floor_clearance, 0.0, 2.0);
  section.readInRange("robot_height", o.robot_height, 0.01, 5.0);
  if (o.robot_height <= o.floor_clearance)
    section.fail("robot_height", "must be > floor_clearance");
  section.read("floor", o.floor);
  if (o.floor != "auto" && o.floor != "given") section.fail("floor", "must be auto or given");
  std::vector<double> up{o.up.x(), o.up.y(), o.up.z()};
  section.read("up", up);
  if (up.size() != 3) section.fail("up", "needs 3 numbers (x y z)");
  o.up = Eigen::Vector3d(up[0], up[1], up[2]);
  if (!(o.up.norm() > 1e-6)) section.fail("up", "must not be zero");
  o.up.normalize();
  section.readInRange("floor_height", o.floor_height, -100.0, 100.0);
  section.rejectUnknownKeys();
  return o;
}

}  // namespace ply_slam
