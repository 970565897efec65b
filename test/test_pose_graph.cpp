// PoseGraph: trajectories with a known truth (a square and a large circle), drift injected
// into the starting poses or into the edges, and a loop edge that closes them.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

#include "ply_slam/mapping/pose_graph.h"
#include "ply_slam/mapping/relative_pose_cost.h"
#include "pose_test_helpers.h"

namespace ply_slam {
namespace {

using namespace ::ply_slam::test;
using Poses = std::vector<Eigen::Isometry3d>;

// Camera looking along the body's x axis (optical frame: z forward, x right, y down), so the
// trajectory's turns are about the camera's y axis.
Eigen::Isometry3d bodyToCamera() {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() << 0, 0, 1, -1, 0, 0, 0, -1, 0;
  return T;
}

// Camera -> world poses around a square of side_m metres, per_side poses a side, heading
// along each side and turning 90 deg at the corners, rising and falling 10 cm on the way.
Poses squarePath(int per_side, double side_m) {
  const Eigen::Vector2d corners[5] = {{0, 0}, {side_m, 0}, {side_m, side_m}, {0, side_m}, {0, 0}};
  const int n = 4 * per_side;
  Poses poses;
  for (int k = 0; k < n; ++k) {
    const int side = k / per_side;
    const double f = static_cast<double>(k % per_side) / per_side;
    const Eigen::Vector2d xy = corners[side] + f * (corners[side + 1] - corners[side]);
    const double height = 0.1 * std::sin(2.0 * kPi * k / n);
    poses.push_back(makePose(Eigen::Vector3d::UnitZ(), 90.0 * side, {xy.x(), xy.y(), height}) *
                    bodyToCamera());
  }
  return poses;
}

// Camera -> world poses on a circle of radius_m, n poses, heading along the circle.
Poses circlePath(int n, double radius_m) {
  Poses poses;
  for (int k = 0; k < n; ++k) {
    const double angle = 2.0 * kPi * k / n;
    const Eigen::Vector3d position(radius_m * std::sin(angle), radius_m * (1.0 - std::cos(angle)),
                                   0.2 * std::sin(3.0 * angle));
    poses.push_back(makePose(Eigen::Vector3d::UnitZ(), angle * kDegreesPerRadian, position) *
                    bodyToCamera());
  }
  return poses;
}

Eigen::Isometry3d relative(const Eigen::Isometry3d& from, const Eigen::Isometry3d& to) {
  return from.inverse() * to;
}

// A small random motion: Gaussian angle-axis (rotation_deg per axis) and translation (m).
class Noise {
 public:
  Noise(unsigned seed, double rotation_deg, double translation_m)
      : rng_(seed), rotation_(rotation_deg / kDegreesPerRadian), translation_(translation_m) {}
  Eigen::Isometry3d operator()() {
    const Eigen::Vector3d w(gauss(), gauss(), gauss());
    const Eigen::Vector3d t(gauss(), gauss(), gauss());
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = Eigen::AngleAxisd(rotation_ * w.norm(), w.normalized()).toRotationMatrix();
    T.translation() = translation_ * t;
    return T;
  }

 private:
  double gauss() { return std::normal_distribution<double>(0.0, 1.0)(rng_); }
  std::mt19937 rng_;
  double rotation_, translation_;
};

// The odometry edges k -> k+1 of a trajectory, each moved by the noise (none: exact).
Poses odometry(const Poses& truth, Noise* noise) {
  Poses edges;
  for (size_t k = 0; k + 1 < truth.size(); ++k) {
    edges.push_back(relative(truth[k], truth[k + 1]) *
                    (noise ? (*noise)() : Eigen::Isometry3d::Identity()));
  }
  return edges;
}

// Dead reckoning: the poses the edges give from the true first pose.
Poses integrate(const Eigen::Isometry3d& first, const Poses& edges) {
  Poses poses{first};
  for (const Eigen::Isometry3d& edge : edges) poses.push_back(poses.back() * edge);
  return poses;
}

double centreError(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return (a.translation() - b.translation()).norm();
}

struct Errors {
  double max_m = 0, max_deg = 0;  // the worst pose's
  double rms_m = 0;               // over all poses (an ATE without alignment)
  double end_m = 0, end_deg = 0;  // the last pose's, where the drift is largest
};

Errors poseErrors(const PoseGraph& graph, const Poses& truth) {
  Errors e;
  for (size_t k = 0; k < truth.size(); ++k) {
    const double m = centreError(graph.pose(k), truth[k]);
    e.max_m = std::max(e.max_m, m);
    e.max_deg = std::max(e.max_deg, rotationErrorDeg(graph.pose(k), truth[k]));
    e.rms_m += m * m;
  }
  e.rms_m = std::sqrt(e.rms_m / truth.size());
  e.end_m = centreError(graph.pose(truth.size() - 1), truth.back());
  e.end_deg = rotationErrorDeg(graph.pose(truth.size() - 1), truth.back());
  return e;
}

struct Correction {
  Errors before, after;
  PoseGraphSummary summary;
};

// Optimises with the default options, measuring the errors before and after (printed).
Correction optimiseAgainst(PoseGraph& graph, const Poses& truth, const char* name) {
  Correction c;
  c.before = poseErrors(graph, truth);
  c.summary = graph.optimise(PoseGraphOptions());
  c.after = poseErrors(graph, truth);
  std::printf(
      "%s, %zu poses %zu edges: end pose %.1f mm %.2f deg -> %.2g mm %.2g deg; worst pose "
      "%.1f mm %.2f deg -> %.2g mm %.2g deg; rms %.1f -> %.2g mm; %d iterations, %.1f ms, "
      "cost %.3g -> %.3g\n",
      name, graph.numPoses(), graph.numEdges(), 1e3 * c.before.end_m, c.before.end_deg,
      1e3 * c.after.end_m, c.after.end_deg, 1e3 * c.before.max_m, c.before.max_deg,
      1e3 * c.after.max_m, c.after.max_deg, 1e3 * c.before.rms_m, 1e3 * c.after.rms_m,
      c.summary.iterations, c.summary.ms, c.summary.initial_cost, c.summary.final_cost);
  return c;
}

// SEED=N in the environment reruns the noisy cases with other noise.
unsigned seed(unsigned fallback) {
  const char* s = std::getenv("SEED");
  return s ? std::atoi(s) : fallback;
}

// Poses (the first fixed), odometry edges, and the loop edge last -> first.
PoseGraph loopGraph(const Poses& initial, const Poses& edges, const Eigen::Isometry3d& loop,
                    double loop_weight) {
  PoseGraph graph;
  for (size_t k = 0; k < initial.size(); ++k) graph.addPose(k, initial[k], k == 0);
  for (size_t k = 0; k < edges.size(); ++k) graph.addEdge(k, k + 1, edges[k]);
  graph.addEdge(initial.size() - 1, 0, loop, loop_weight);
  return graph;
}

// The true edges, drifted starting poses: the truth is the graph's exact minimum, and the
// first pose pins the gauge, so every pose must come back.
TEST(PoseGraph, ExactEdgesBringDriftedPosesBack) {
  const Poses truth = squarePath(5, 1.5);
  Noise noise(seed(7), 0.5, 0.005);
  const Poses initial = integrate(truth[0], odometry(truth, &noise));
  const Eigen::Isometry3d loop = relative(truth.back(), truth.front());
  PoseGraph graph = loopGraph(initial, odometry(truth, nullptr), loop, 1.0);
  ASSERT_EQ(graph.numPoses(), 20u);
  ASSERT_EQ(graph.numEdges(), 20u);

  const double gap_m = centreError(initial.back() * loop, initial.front());
  const double gap_deg = rotationErrorDeg(initial.back() * loop, initial.front());
  std::printf("square, exact edges: the loop misses by %.1f mm %.2f deg\n", 1e3 * gap_m, gap_deg);
  const Correction c = optimiseAgainst(graph, truth, "square, exact edges");

  // The drift is real: poses start several cm and degrees off (their worst 45 mm and 2.0 deg
  // at the least over SEED 1-40), and the loop misses by several cm.
  EXPECT_GT(c.before.max_m, 0.03);
  EXPECT_GT(c.before.max_deg, 1.5);
  EXPECT_TRUE(c.summary.converged);
  EXPECT_LT(c.after.max_m, 0.001);
  EXPECT_LT(c.after.max_deg, 0.1);
  EXPECT_EQ(centreError(graph.pose(0), truth[0]), 0.0);  // fixed
}

// Noisy odometry edges and dead-reckoned poses: the exact loop edge pulls the end back to
// the start and spreads the gap over the trajectory.
TEST(PoseGraph, LoopEdgeSpreadsOdometryDrift) {
  const Poses truth = squarePath(10, 2.0);
  Noise noise(seed(11), 0.3, 0.003);
  const Poses edges = odometry(truth, &noise);
  const Poses initial = integrate(truth[0], edges);
  PoseGraph graph = loopGraph(initial, edges, relative(truth.back(), truth.front()), 1.0);

  const Correction c = optimiseAgainst(graph, truth, "square, noisy edges");

  // The end pose comes back to within about one odometry edge's noise. Over SEED 1-40 its
  // error dropped 42-460 times in position and 8.5-63 times in rotation. Poses in the middle
  // keep their share of the random walk, which one loop cannot observe: the worst pose does
  // not always improve, and the RMS over all poses dropped 0.83-6.4 times.
  EXPECT_TRUE(c.summary.converged);
  EXPECT_LT(c.after.end_m, c.before.end_m / 10.0);
  EXPECT_LT(c.after.end_deg, c.before.end_deg / 5.0);
}

TEST(PoseGraph, BadInputThrows) {
  PoseGraph graph;
  const Eigen::Isometry3d I = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d nan_pose = I;
  nan_pose.translation().x() = std::numeric_limits<double>::quiet_NaN();
  graph.addPose(1, I, true);
  graph.addPose(2, I);
  EXPECT_THROW(graph.addPose(2, I), std::invalid_argument);  // twice
  EXPECT_THROW(graph.addPose(3, nan_pose), std::invalid_argument);
  EXPECT_THROW(graph.addEdge(1, 9, I), std::invalid_argument);  // unknown "to"
  EXPECT_THROW(graph.addEdge(9, 1, I), std::invalid_argument);  // unknown "from"
  EXPECT_THROW(graph.addEdge(1, 1, I), std::invalid_argument);  // self
  EXPECT_THROW(graph.addEdge(1, 2, nan_pose), std::invalid_argument);
  EXPECT_THROW(graph.addEdge(1, 2, I, 0.0), std::invalid_argument);
  EXPECT_THROW(graph.addEdge(1, 2, I, -1.0), std::invalid_argument);
  EXPECT_THROW(graph.addEdge(1, 2, I, std::numeric_limits<double>::infinity()),
               std::invalid_argument);
  EXPECT_THROW(graph.pose(3), std::out_of_range);
  EXPECT_EQ(graph.numPoses(), 2u);
  EXPECT_EQ(graph.numEdges(), 0u);

  graph.addEdge(1, 2, I);
  PoseGraphOptions bad;
  bad.translation_sigma_m = 0.0;
  EXPECT_THROW(graph.optimise(bad), std::invalid_argument);
  bad = PoseGraphOptions();
  bad.max_iterations = 0;
  EXPECT_THROW(graph.optimise(bad), std::invalid_argument);
}

// No fixed pose: the first one added (not the smallest id) holds the gauge.
TEST(PoseGraph, WithoutFixedPoseTheFirstAddedStays) {
  const Poses truth = squarePath(2, 1.0);
  const Eigen::Isometry3d start = makePose({1, 0, 0}, 10.0, {0.1, 0.2, 0.3}) * truth[2];
  PoseGraph graph;
  graph.addPose(2, start);
  for (long k : {0, 1, 3}) graph.addPose(k, truth[k]);
  for (long k : {0, 1, 2}) graph.addEdge(k, k + 1, relative(truth[k], truth[k + 1]));
  const PoseGraphSummary summary = graph.optimise(PoseGraphOptions());
  EXPECT_TRUE(summary.converged);
  EXPECT_TRUE(graph.pose(2).isApprox(start, 1e-12));
  // The others follow pose 2 rigidly: their true relative poses to it are restored.
  for (long k : {0, 1, 3}) {
    const Eigen::Isometry3d expected = start * relative(truth[2], truth[k]);
    EXPECT_LT(centreError(graph.pose(k), expected), 1e-6) << k;
    EXPECT_LT(rotationErrorDeg(graph.pose(k), expected), 1e-5) << k;
  }
}

TEST(PoseGraph, EmptyGraphAndLonePosesStay) {
  PoseGraph empty;
  PoseGraphSummary summary = empty.optimise(PoseGraphOptions());
  EXPECT_TRUE(summary.converged);
  EXPECT_EQ(summary.iterations, 0);

  const Eigen::Isometry3d lone = makePose({0, 1, 0}, 30.0, {1, 2, 3});
  PoseGraph graph;
  graph.addPose(0, Eigen::Isometry3d::Identity(), true);
  graph.addPose(1, Eigen::Isometry3d::Identity());
  graph.addPose(2, lone);  // on no edge
  graph.addEdge(0, 1, lone);
  summary = graph.optimise(PoseGraphOptions());
  EXPECT_TRUE(summary.converged);
  EXPECT_LT(centreError(graph.pose(1), lone), 1e-6);
  EXPECT_LT(rotationErrorDeg(graph.pose(1), lone), 1e-5);
  EXPECT_TRUE(graph.pose(2).isApprox(lone, 1e-15));  // untouched
}

// exp of se(3): rotation exp(omega), translation V(omega) rho.
Eigen::Isometry3d se3Exp(const Eigen::Vector3d& omega, const Eigen::Vector3d& rho) {
  const double theta = omega.norm();
  Eigen::Matrix3d W;
  W << 0, -omega.z(), omega.y(), omega.z(), 0, -omega.x(), -omega.y(), omega.x(), 0;
  const Eigen::Matrix3d V = Eigen::Matrix3d::Identity() +
                            (1.0 - std::cos(theta)) / (theta * theta) * W +
                            (theta - std::sin(theta)) / (theta * theta * theta) * W * W;
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(theta, omega / theta).toRotationMatrix();
  T.translation() = V * rho;
  return T;
}

// The residual of an edge whose estimate is exp(xi) away from its measurement is xi, scaled.
TEST(PoseGraph, ResidualIsTheLogOfTheEdgeError) {
  const Eigen::Isometry3d T_wa = makePose({0.2, -1, 0.5}, 40.0, {1, -2, 0.5});
  const Eigen::Isometry3d measured = makePose({1, 1, 0}, 25.0, {0.3, 0.1, -0.2});
  for (double angle : {1e-3, 0.05, 1.0, 3.0}) {
    const Eigen::Vector3d omega = angle * Eigen::Vector3d(0.6, -0.48, 0.64);
    const Eigen::Vector3d rho(0.4, -0.25, 0.9);
    const Eigen::Isometry3d T_wb = T_wa * measured * se3Exp(omega, rho);
    const Eigen::Quaterniond qa(T_wa.rotation()), qb(T_wb.rotation());
    const Eigen::Vector3d ta = T_wa.translation(), tb = T_wb.translation();
    const RelativePoseCost cost(measured, 2.0, 3.0);
    double residual[6];
    ASSERT_TRUE(cost(qa.coeffs().data(), ta.data(), qb.coeffs().data(), tb.data(), residual));
    for (int i = 0; i < 3; ++i) {
      EXPECT_NEAR(residual[i], 2.0 * omega[i], 1e-9) << "angle " << angle << " i " << i;
      EXPECT_NEAR(residual[i + 3], 3.0 * rho[i], 1e-9) << "angle " << angle << " i " << i;
    }
  }
}

// A 500-keyframe circle (50 m) with noisy odometry and skip-one covisibility edges, and three
// loop edges at the closure: the size a long run's essential graph reaches.
TEST(PoseGraph, FiveHundredPosesWithLoop) {
  const int n = 500;
  const Poses truth = circlePath(n, 8.0);
  Noise noise(seed(5), 0.2, 0.002);
  const Poses edges = odometry(truth, &noise);
  const Poses initial = integrate(truth[0], edges);
  PoseGraph graph = loopGraph(initial, edges, relative(truth[n - 1], truth[0]), 1.0);
  for (int k = 0; k + 2 < n; ++k)
    graph.addEdge(k, k + 2, relative(truth[k], truth[k + 2]) * noise(), 0.5);
  graph.addEdge(n - 2, 0, relative(truth[n - 2], truth[0]));
  graph.addEdge(n - 1, 1, relative(truth[n - 1], truth[1]));

  const Correction c = optimiseAgainst(graph, truth, "circle");

  // Over SEED 1-40: 9-10 iterations, the end pose's error dropped 80-9000 times in position
  // and 20-280 times in rotation, the RMS over all poses 1.5-20 times.
  EXPECT_TRUE(c.summary.converged);
  EXPECT_LT(c.after.end_m, c.before.end_m / 10.0);
  EXPECT_LT(c.after.end_deg, c.before.end_deg / 10.0);
  EXPECT_LT(c.after.rms_m, c.before.rms_m / 1.25);
}

}  // namespace
}  // namespace ply_slam
