#pragma once

#include <ceres/ceres.h>

#include "ply_slam/common/solver_options.h"

namespace ply_slam {

// Ceres' options for a solve with these settings, silent.
ceres::Solver::Options toCeres(const SolverOptions& options);

}  // namespace ply_slam
