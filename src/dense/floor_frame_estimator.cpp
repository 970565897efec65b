#include "ply_slam/dense/floor_frame_estimator.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "ply_slam/common/statistics.h"
#include "ply_slam/dense/top_view_renderer.h"

namespace ply_slam {
namespace {

constexpr double kMaxTiltCos = 0.866;  // cos 30 deg: the floor's normal against the guessed up
constexpr size_t kMinSupport = 50;     // voxels: 0.125 m^2 of floor at 5 cm
constexpr int kRansacIterations = 500;
// m; the inliers' spread across their main direction. A wall's row of voxels also lies in a
// level plane; a floor (or a table top) spreads both ways.
constexpr double kMinSpread = 0.1;

struct Plane {
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  double offset = 0.0;  // normal . p on the plane
  size_t support = 0;
};

size_t countNear(const std::vector<Eigen::Vector3d>& points, const Plane& plane, double tolerance,
                 std::vector<Eigen::Vector3d>* near = nullptr) {
  size_t n = 0;
  for (const auto& p : points)
    if (std::abs(plane.normal.dot(p) - plane.offset) <= tolerance) {
      ++n;
      if (near) near->push_back(p);
    }
  return n;
}

// Centroid and principal axes of points (eigenvalues of the covariance, ascending).
struct Spread {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  Eigen::Vector3d variances = Eigen::Vector3d::Zero();
  Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();
};

Spread spreadOf(const std::vector<Eigen::Vector3d>& points) {
  Spread s;
  if (points.empty()) return s;
  for (const auto& p : points) s.mean += p;
  s.mean /= static_cast<double>(points.size());
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (const auto& p : points) covariance += (p - s.mean) * (p - s.mean).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(covariance / points.size());
  s.variances = solver.eigenvalues();
  s.axes = solver.eigenvectors();
  return s;
}

// Least squares: the plane through the centroid normal to the least spread direction.
Plane fitted(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& up) {
  const Spread spread = spreadOf(points);
  Plane plane;
  plane.normal = spread.axes.col(0);
  if (plane.normal.dot(up) < 0.0) plane.normal = -plane.normal;
  plane.offset = plane.normal.dot(spread.mean);
  return plane;
}

// Standard deviation of the points across the direction they spread most in.
double secondSpread(const std::vector<Eigen::Vector3d>& points) {
  return std::sqrt(std::max(0.0, spreadOf(points).variances(1)));
}

// RANSAC over three-point planes near the guessed up, then refits on the inliers.
Plane floorPlane(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& up,
                 double tolerance) {
  Plane best;
  if (points.size() < 3) return best;
  std::mt19937 rng(7);  // fixed: the same map gives the same grid
  std::uniform_int_distribution<size_t> pick(0, points.size() - 1);
  for (int k = 0; k < kRansacIterations; ++k) {
    const Eigen::Vector3d &a = points[pick(rng)], &b = points[pick(rng)], &c = points[pick(rng)];
    Plane plane;
    plane.normal = (b - a).cross(c - a);
    if (plane.normal.norm() < 1e-9) continue;
    plane.normal.normalize();
    if (plane.normal.dot(up) < 0.0) plane.normal = -plane.normal;
    if (plane.normal.dot(up) < kMaxTiltCos) continue;
    plane.offset = plane.normal.dot(a);
    plane.support = countNear(points, plane, tolerance);
    if (plane.support <= best.support) continue;
    std::vector<Eigen::Vector3d> inliers;
    countNear(points, plane, tolerance, &inliers);
    if (secondSpread(inliers) >= kMinSpread) best = plane;
  }
  // Least-squares refits on ever closer inliers: the lowest voxels of walls and furniture lie
  // within a voxel of the floor too, and would tilt it towards them.
  for (double share : {1.0, 0.5, 0.25}) {
    if (best.support < kMinSupport) break;
    std::vector<Eigen::Vector3d> inliers;
    if (countNear(points, best, share * tolerance, &inliers) < kMinSupport) break;
    Plane refit = fitted(inliers, up);
    if (refit.normal.dot(up) < kMaxTiltCos) break;
    refit.support = countNear(points, refit, tolerance);
    best = refit;
  }
  return best;
}

// The floor is the lowest of the large level planes: a hand-held camera over a desk may see
// more desk top than floor. Below the best plane, a plane with a quarter of its support wins.
Plane lowestPlane(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& up,
                  double tolerance) {
  Plane best = floorPlane(points, up, tolerance);
  while (best.support >= kMinSupport) {
    std::vector<Eigen::Vector3d> lower;
    for (const auto& p : points)
      if (best.normal.dot(p) < best.offset - 3.0 * tolerance) lower.push_back(p);
    const Plane below = floorPlane(lower, up, tolerance);
    if (below.support < std::max(kMinSupport, best.support / 4)) break;
    best = below;
  }
  return best;
}

}  // namespace

FloorFrameEstimator::FloorFrameEstimator(const OccupancyGridOptions& options) : options_(options) {}

Eigen::Isometry3d FloorFrameEstimator::frameOn(const Eigen::Vector3d& up_in, double height,
                                               const Trajectory& trajectory) {
  const Eigen::Vector3d up = up_in.normalized();
  Eigen::Isometry3d first = trajectory.empty() ? Eigen::Isometry3d::Identity() : trajectory[0].T_wc;
  const Eigen::Vector3d c = first.translation();
  Eigen::Vector3d x = first.linear().col(2);  // the camera's view
  x -= x.dot(up) * up;
  if (x.norm() < 0.1) {  // looking straight down or up: its right-hand side instead
    x = first.linear().col(0);
    x -= x.dot(up) * up;
  }
  x.normalize();
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear().col(0) = x;
  T.linear().col(1) = up.cross(x);
  T.linear().col(2) = up;
  T.translation() = c - (up.dot(c) - height) * up;
  return T;
}

FloorFrame FloorFrameEstimator::estimate(const std::vector<Eigen::Vector3d>& points,
                                         double voxel_size, const Trajectory& trajectory) const {
  FloorFrame floor;
  if (options_.floor == "given") {
    floor.T_world_floor = frameOn(options_.up, options_.floor_height, trajectory);
    return floor;
  }
  const Eigen::Vector3d up = TopViewRenderer::upFromTrajectory(trajectory);
  double lowest_camera = std::numeric_limits<double>::infinity();
  for (const auto& pose : trajectory)
    lowest_camera = std::min(lowest_camera, up.dot(pose.T_wc.translation()));
  std::vector<Eigen::Vector3d> below;
  for (const auto& p : points)
    if (up.dot(p) < lowest_camera) below.push_back(p);

  const Plane plane = lowestPlane(below, up, voxel_size);
  if (plane.support >= kMinSupport) {
    floor.T_world_floor = frameOn(plane.normal, plane.offset, trajectory);
    floor.method = "plane";
    floor.support = plane.support;
    return floor;
  }
  // No floor seen: the lowest static voxels (2nd percentile, past stray ones) under the guess.
  std::vector<double> heights;
  for (const auto& p : below) heights.push_back(up.dot(p));
  double height = std::isfinite(lowest_camera) ? lowest_camera : 0.0;
  if (!heights.empty()) height = kthSmallest(heights, heights.size() / 50) - 0.5 * voxel_size;
  floor.T_world_floor = frameOn(up, height, trajectory);
  floor.method = "lowest";
  return floor;
}

}  // namespace ply_slam
