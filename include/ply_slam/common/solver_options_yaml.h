#pragma once

#include <string>

#include "ply_slam/common/config_section.h"
#include "ply_slam/common/solver_options.h"

namespace ply_slam {

// Reads a solver section (keys: linear_solver, max_iterations, function_tolerance,
// gradient_tolerance, parameter_tolerance, num_threads) over `defaults`, the module's own
// settings: an absent section or key keeps them. Unknown keys, an unknown solver name and values
// out of range throw ConfigError naming the file and key.
SolverOptions readSolverOptions(ConfigSection section, const SolverOptions& defaults);
// One linear solver's name under `key` (absent: `solver` unchanged).
void readLinearSolver(ConfigSection& section, const std::string& key, LinearSolver& solver);

}  // namespace ply_slam
