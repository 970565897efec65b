#include "ply_slam/mapping/pose_graph.h"

#include <ceres/ceres.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "ply_slam/common/ceres_solver_options.h"
#include "ply_slam/common/stopwatch.h"
#include "ply_slam/mapping/relative_pose_cost.h"

namespace ply_slam {
namespace {

bool isFinite(const Eigen::Isometry3d& T) { return T.matrix().allFinite(); }

void checkOptions(const PoseGraphOptions& options) {
  if (options.max_iterations <= 0 || options.num_threads <= 0) {
    throw std::invalid_argument("PoseGraph: max_iterations and num_threads must be positive");
  }
  if (!(options.rotation_sigma_rad > 0.0) || !(options.translation_sigma_m > 0.0)) {
    throw std::invalid_argument(
        "PoseGraph: rotation_sigma_rad and translation_sigma_m must be "
        "positive");
  }
}

ceres::Solver::Options solverOptions(const PoseGraphOptions& options) {
  SolverOptions solver;  // Ceres' tolerances
  solver.linear_solver = options.linear_solver;
  solver.max_iterations = options.max_iterations;
  solver.num_threads = options.num_threads;
  return toCeres(solver);
}

}  // namespace

void PoseGraph::addPose(long id, const Eigen::Isometry3d& T_wc, bool fixed) {
  if (!isFinite(T_wc)) {
    throw std::invalid_argument("PoseGraph::addPose: pose " + std::to_string(id) +
                                " has a non-finite entry");
  }
  if (vertices_.empty()) first_id_ = id;
  if (!vertices_.emplace(id, makeVertex(T_wc, fixed)).second) {
    throw std::invalid_argument("PoseGraph::addPose: pose " + std::to_string(id) +
                                " is already in the graph");
  }
}

void PoseGraph::addEdge(long from, long to, const Eigen::Isometry3d& T_from_to, double weight) {
  const std::string name =
      "PoseGraph::addEdge " + std::to_string(from) + " -> " + std::to_string(to) + ": ";
  vertex(from, "from");
  vertex(to, "to");
  if (from == to) throw std::invalid_argument(name + "an edge must join two different poses");
  if (!isFinite(T_from_to)) throw std::invalid_argument(name + "non-finite relative pose");
  if (!(weight > 0.0) || !std::isfinite(weight)) {
    throw std::invalid_argument(name + "weight " + std::to_string(weight) +
                                " is not positive and finite");
  }
  edges_.push_back({from, to, T_from_to, weight});
}

PoseGraphSummary PoseGraph::optimise(const PoseGraphOptions& options) {
  checkOptions(options);
  PoseGraphSummary summary;
  if (edges_.empty()) {
    summary.converged = true;
    return summary;
  }
  Stopwatch watch;
  // Declared before the problem, which does not own it, so it outlives the problem.
  ceres::EigenQuaternionManifold quaternion_manifold;
  ceres::Problem::Options problem_options;
  problem_options.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem problem(problem_options);
  buildProblem(options, &quaternion_manifold, problem);

  ceres::Solver::Summary ceres_summary;
  ceres::Solve(solverOptions(options), &problem, &ceres_summary);
  readBack(ceres_summary.IsSolutionUsable());
  summary.iterations = ceres_summary.num_successful_steps + ceres_summary.num_unsuccessful_steps;
  summary.initial_cost = ceres_summary.initial_cost;
  summary.final_cost = ceres_summary.final_cost;
  summary.converged = ceres_summary.termination_type == ceres::CONVERGENCE;
  summary.ms = watch.elapsedMs();
  return summary;
}

void PoseGraph::buildProblem(const PoseGraphOptions& options, ceres::Manifold* quaternion_manifold,
                             ceres::Problem& problem) {
  for (const Edge& e : edges_) {
    const double sqrt_weight = std::sqrt(e.weight);
    Vertex& a = vertices_.at(e.from);
    Vertex& b = vertices_.at(e.to);
    problem.AddResidualBlock(
        RelativePoseCost::create(e.T_from_to, sqrt_weight / options.rotation_sigma_rad,
                                 sqrt_weight / options.translation_sigma_m),
        nullptr, a.rotation.data(), a.translation.data(), b.rotation.data(), b.translation.data());
  }
  const bool hold_first = !anyFixed();
  for (auto& [id, v] : vertices_) {
    if (!problem.HasParameterBlock(v.rotation.data())) continue;  // on no edge
    problem.SetManifold(v.rotation.data(), quaternion_manifold);
    if (v.fixed || (hold_first && id == first_id_)) {
      problem.SetParameterBlockConstant(v.rotation.data());
      problem.SetParameterBlockConstant(v.translation.data());
    }
  }
}

void PoseGraph::readBack(bool solution_usable) {
  for (auto& [id, v] : vertices_) {
    if (solution_usable) {
      v.T_wc.linear() = Eigen::Map<const Eigen::Quaterniond>(v.rotation.data()).toRotationMatrix();
      v.T_wc.translation() = Eigen::Map<const Eigen::Vector3d>(v.translation.data());
    } else {
      v = makeVertex(v.T_wc, v.fixed);  // a failed solve leaves the poses as they were
    }
  }
}

const Eigen::Isometry3d& PoseGraph::pose(long id) const {
  const auto it = vertices_.find(id);
  if (it == vertices_.end()) {
    throw std::out_of_range("PoseGraph::pose: no pose " + std::to_string(id));
  }
  return it->second.T_wc;
}

PoseGraph::Vertex PoseGraph::makeVertex(const Eigen::Isometry3d& T_wc, bool fixed) {
  Vertex v;
  // rotation() is the orthonormal part, so a slightly non-orthonormal input still gives a
  // unit quaternion.
  const Eigen::Quaterniond q = Eigen::Quaterniond(T_wc.rotation()).normalized();
  Eigen::Map<Eigen::Quaterniond>(v.rotation.data()) = q;
  Eigen::Map<Eigen::Vector3d>(v.translation.data()) = T_wc.translation();
  v.T_wc.setIdentity();
  v.T_wc.linear() = q.toRotationMatrix();
  v.T_wc.translation() = T_wc.translation();
  v.fixed = fixed;
  return v;
}

PoseGraph::Vertex& PoseGraph::vertex(long id, const char* role) {
  const auto it = vertices_.find(id);
  if (it == vertices_.end()) {
    throw std::invalid_argument("PoseGraph::addEdge: the " + std::string(role) + " pose " +
                                std::to_string(id) + " is not in the graph (add it first)");
  }
  return it->second;
}

bool PoseGraph::anyFixed() const {
  for (const auto& [id, v] : vertices_) {
    if (v.fixed) return true;
  }
  return false;
}

}  // namespace ply_slam
