#include "ply_slam/common/ceres_solver_options.h"

namespace ply_slam {
namespace {

ceres::LinearSolverType ceresType(LinearSolver solver) {
  switch (solver) {
    case LinearSolver::kDenseQr:
      return ceres::DENSE_QR;
    case LinearSolver::kDenseSchur:
      return ceres::DENSE_SCHUR;
    case LinearSolver::kSparseSchur:
      return ceres::SPARSE_SCHUR;
    case LinearSolver::kSparseNormalCholesky:
      return ceres::SPARSE_NORMAL_CHOLESKY;
  }
  return ceres::DENSE_QR;
}

}  // namespace

ceres::Solver::Options toCeres(const SolverOptions& options) {
  ceres::Solver::Options ceres_options;
  ceres_options.linear_solver_type = ceresType(options.linear_solver);
  ceres_options.max_num_iterations = options.max_iterations;
  ceres_options.function_tolerance = options.function_tolerance;
  ceres_options.gradient_tolerance = options.gradient_tolerance;
  ceres_options.parameter_tolerance = options.parameter_tolerance;
  ceres_options.num_threads = options.num_threads;
  ceres_options.logging_type = ceres::SILENT;
  return ceres_options;
}

}  // namespace ply_slam
