#include "ply_slam/mapping/local_mapping_options_yaml.h"

#include "ply_slam/common/solver_options_yaml.h"

namespace ply_slam {

LocalMappingOptions readLocalMappingOptions(ConfigSection section) {
  LocalMappingOptions o;
  section.readInRange("fuse_radius_px", o.fuse_radius_px, 0.5, 100.0);
  section.readInRange("fuse_max_descriptor_distance", o.fuse_max_descriptor_distance, 0, 256);
  o.bundle_solver = readSolverOptions(section.child("bundle_solver"), o.bundle_solver);
  section.rejectUnknownKeys();
  return o;
}

}  // namespace ply_slam
