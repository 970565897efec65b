#pragma once

#include "ply_slam/common/enum_words.h"

namespace ply_slam {

// Ceres' linear solvers that fit our problems: DENSE_QR for one pose, SPARSE_SCHUR for bundle
// adjustment (poses and points), SPARSE_NORMAL_CHOLESKY for a pose graph.
enum class LinearSolver { kDenseQr, kDenseSchur, kSparseSchur, kSparseNormalCholesky };
inline constexpr EnumWord<LinearSolver> kLinearSolverWords[] = {
    {LinearSolver::kDenseQr, "dense_qr"},
    {LinearSolver::kDenseSchur, "dense_schur"},
    {LinearSolver::kSparseSchur, "sparse_schur"},
    {LinearSolver::kSparseNormalCholesky, "sparse_normal_cholesky"}};

// The settings of one Ceres solve. The tolerances default to Ceres' own defaults (a test
// holds them to ceres::Solver::Options), so that only what a module sets differs from Ceres.
struct SolverOptions {
  LinearSolver linear_solver = LinearSolver::kDenseQr;
  int max_iterations = 50;
  double function_tolerance = 1e-6;  // stop once an iteration changes the cost by less (share)
  double gradient_tolerance = 1e-10;
  double parameter_tolerance = 1e-8;
  int num_threads = 1;  // the tracker and the mapper already share two cores
};

}  // namespace ply_slam
