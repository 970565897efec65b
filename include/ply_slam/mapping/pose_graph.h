#pragma once

#include <Eigen/Geometry>
#include <array>
#include <cstddef>
#include <map>
#include <vector>

#include "ply_slam/mapping/pose_graph_options.h"

namespace ceres {
class Manifold;
class Problem;
}  // namespace ceres

namespace ply_slam {

struct PoseGraphSummary {
  int iterations = 0;                       // Levenberg-Marquardt steps, taken and rejected
  double initial_cost = 0, final_cost = 0;  // Ceres' cost: half the sum of squared residuals
  double ms = 0;                            // wall time of optimise(), problem set-up included
  bool converged = false;  // Ceres stopped on a tolerance, not on max_iterations or a failure
};

// An SE(3) pose graph solved with Ceres: keyframe poses joined by relative-pose edges (the
// spanning tree, covisibility, loops), for spreading a loop's correction along the trajectory.
// Each pose is a unit quaternion (on Ceres' EigenQuaternionManifold) and a translation, so the
// steps stay on SE(3). Fixed poses do not move. The graph's gauge (where the whole trajectory
// sits) is unobservable from relative edges: when no pose is fixed, optimise() holds the first
// pose added in place (without marking it fixed). An empty graph or one without edges is
// already optimal: optimise() returns at once, converged. Poses no edge touches do not move.
class PoseGraph {
 public:
  // A vertex: a keyframe's camera -> world pose T_wc. Throws std::invalid_argument for an id
  // already added or a pose with a non-finite entry.
  void addPose(long id, const Eigen::Isometry3d& T_wc, bool fixed = false);
  // A relative-pose edge, T_from_to = T_wc(from)^-1 * T_wc(to) as measured (the "to" camera in
  // the "from" camera's frame). weight scales the information (the inverse covariance):
  // covisibility strength, loop edges. Throws std::invalid_argument for an unknown or equal
  // from / to, a non-finite measurement or a weight that is not positive and finite.
  void addEdge(long from, long to, const Eigen::Isometry3d& T_from_to, double weight = 1.0);

  // Moves the free poses to the least-squares fit of all edges. Throws std::invalid_argument
  // for options out of range (non-positive sigmas, iterations or threads).
  PoseGraphSummary optimise(const PoseGraphOptions& options);

  // The current estimate of a pose; throws std::out_of_range for an unknown id.
  const Eigen::Isometry3d& pose(long id) const;
  bool hasPose(long id) const { return vertices_.count(id) > 0; }
  size_t numPoses() const { return vertices_.size(); }
  size_t numEdges() const { return edges_.size(); }

 private:
  struct Vertex {
    Eigen::Isometry3d T_wc;
    std::array<double, 4> rotation;     // what Ceres moves: Eigen quaternion (x, y, z, w)
    std::array<double, 3> translation;  // and translation of T_wc
    bool fixed = false;
  };
  struct Edge {
    long from = 0, to = 0;
    Eigen::Isometry3d T_from_to;
    double weight = 1.0;
  };

  // One residual per edge; the manifold on every rotation; fixed poses (or the gauge) constant.
  void buildProblem(const PoseGraphOptions& options, ceres::Manifold* quaternion_manifold,
                    ceres::Problem& problem);
  // The solved quaternions and translations into T_wc, or, after a failed solve, the reverse.
  void readBack(bool solution_usable);
  static Vertex makeVertex(const Eigen::Isometry3d& T_wc, bool fixed);
  Vertex& vertex(long id, const char* role);  // throws std::invalid_argument naming the role
  bool anyFixed() const;

  std::map<long, Vertex> vertices_;  // ordered: the same graph always gives the same problem
  std::vector<Edge> edges_;
  long first_id_ = 0;  // the first pose added: held in place when none is fixed
};

}  // namespace ply_slam
