#include "ply_slam/mapping/local_mapping_options_yaml.h"

#include "ply_slam/common/solver_options_yaml.h"

namespace ply_slam {

LocalMappingOptions readLocalMappingOptions(ConfigSection section) {
  LocalMappingOptions o;
  o.bundle_solver = readSolverOptions(section.child("bundle_solver"), o.bundle_solver);
  section.rejectUnknownKeys();
  return o;
}

}  // namespace ply_slam
