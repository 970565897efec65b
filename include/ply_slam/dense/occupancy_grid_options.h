#pragma once

#include <Eigen/Core>
#include <string>

namespace ply_slam {

// The 2D occupancy grid for navigation (OccupancyGridBuilder); the config's grid section.
// Heights are measured up from the floor plane.
struct OccupancyGridOptions {
  bool enabled = true;       // with dense.enabled: the grid beside the dense maps
  double resolution = 0.05;  // m, cell edge (the octree's voxel is a sensible choice)
  // A cell is occupied where the octree has an occupied voxel whose surface (the mean of its
  // hits) lies in [floor_clearance, robot_height] above the floor. The floor's own voxels
  // scatter about the plane by the depth noise (Kinect: 2.3 cm at 4 m; a D435i about 2 % of
  // the range) and the keyframes' pose error: 0.1 m keeps them out.
  double floor_clearance = 0.1;
  // TurtleBot3 Waffle Pi: 0.141 m tall with the camera on its front plate; one 5 cm voxel of
  // overlap and 5 cm for what it carries.
  double robot_height = 0.25;
  // "auto": the floor plane fitted to the octree (the SLAM world is the first camera's frame,
  // with no gravity in it); "given": `up` and `floor_height` below.
  std::string floor = "auto";
  // floor: given. The up direction in the SLAM world (-y for a camera held level at the start)
  // and the floor's position along it (m): -1.2 for a level camera 1.2 m above the floor.
  Eigen::Vector3d up = Eigen::Vector3d(0.0, -1.0, 0.0);
  double floor_height = -1.0;
};

}  // namespace ply_slam
