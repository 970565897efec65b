#include "ply_slam/common/solver_options_yaml.h"

namespace ply_slam {

SolverOptions readSolverOptions(ConfigSection section, const SolverOptions& defaults) {
  SolverOptions o = defaults;
  readLinearSolver(section, "linear_solver", o.linear_solver);
  section.readInRange("max_iterations", o.max_iterations, 1, 100000);
  section.readInRange("function_tolerance", o.function_tolerance, 0.0, 1.0);
  section.readInRange("gradient_tolerance", o.gradient_tolerance, 0.0, 1.0);
  section.readInRange("parameter_tolerance", o.parameter_tolerance, 0.0, 1.0);
  section.readInRange("num_threads", o.num_threads, 1, 64);
  section.rejectUnknownKeys();
  return o;
}

void readLinearSolver(ConfigSection& section, const std::string& key, LinearSolver& solver) {
  section.readWord(key, solver, kLinearSolverWords,
                   "must be dense_qr, dense_schur, sparse_schur or sparse_normal_cholesky");
}

}  // namespace ply_slam
