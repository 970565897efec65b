// PoseOptimizer on synthetic scenes with a known pose: accuracy under pixel and depth noise,
// rejection of 30 % gross outliers, and degenerate inputs (no observations, points behind).
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <random>
#include <vector>

#include "ply_slam/common/ceres_solver_options.h"
#include "ply_slam/common/chi_square.h"
#include "ply_slam/common/point_residual.h"
#include "ply_slam/tracking/pose_optimizer.h"
#include "pose_test_helpers.h"

namespace ply_slam {
namespace {

using namespace ::ply_slam::test;

struct Scene {
  std::vector<PointObservation> observations;
  std::vector<bool> is_outlier;
  int outliers = 0;
};

// `n` points 1-4 m in front of the camera at T_cw; 2/3 with depth; a fraction `outlier_ratio`
// replaced by random pixels (and random depths) anywhere in the image.
Scene makeScene(const PinholeCamera& camera, const Eigen::Isometry3d& T_cw, int n,
                double outlier_ratio, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u_dist(0.0, camera.width);
  std::uniform_real_distribution<double> v_dist(0.0, camera.height);
  std::uniform_real_distribution<double> z_dist(1.0, 4.0);
  std::uniform_real_distribution<double> any_depth(0.5, 5.0);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::normal_distribution<double> gauss(0.0, 1.0);
  const Eigen::Isometry3d T_wc = T_cw.inverse();

  Scene scene;
  for (int i = 0; i < n; ++i) {
    const double z = z_dist(rng);
    const Eigen::Vector3d p_c = camera.backProject({u_dist(rng), v_dist(rng)}, z);
    PointObservation o;
    o.world = T_wc * p_c;
    o.pixel = camera.project(p_c) + 0.5 * Eigen::Vector2d(gauss(rng), gauss(rng));
    o.pixel_sigma = 1.0;
    if (i % 3 != 2) {
      o.depth_sigma = std::sqrt(camera.depth_noise.variance(z));
      o.depth = z + o.depth_sigma * gauss(rng);
    }
    const bool outlier = unit(rng) < outlier_ratio;
    if (outlier) {
      o.pixel = {u_dist(rng), v_dist(rng)};
      if (o.depth > 0) o.depth = any_depth(rng);
    }
    scene.observations.push_back(o);
    scene.is_outlier.push_back(outlier);
    scene.outliers += outlier;
  }
  return scene;
}

struct Outcome {
  double translation_error = 0, rotation_error_deg = 0;
  double outliers_flagged = 0, inliers_kept = 0;  // fractions
  int returned = 0, counted = 0;
};

Outcome solve(const Scene& scene, const Eigen::Isometry3d& T_true, unsigned seed) {
  const PoseOptimizer optimizer(makeCamera(), PoseOptimizerParams());
  Eigen::Isometry3d T = perturbed(T_true, seed);
  std::vector<bool> inlier;
  Outcome out;
  out.returned = optimizer.optimize(scene.observations, T, inlier);
  EXPECT_EQ(inlier.size(), scene.observations.size());
  int flagged = 0, kept = 0;
  for (size_t i = 0; i < inlier.size(); ++i) {
    out.counted += inlier[i];
    if (scene.is_outlier[i])
      flagged += !inlier[i];
    else
      kept += inlier[i];
  }
  const int inliers = static_cast<int>(scene.observations.size()) - scene.outliers;
  out.outliers_flagged = scene.outliers ? static_cast<double>(flagged) / scene.outliers : 1.0;
  out.inliers_kept = static_cast<double>(kept) / inliers;
  out.translation_error = translationError(T, T_true);
  out.rotation_error_deg = rotationErrorDeg(T, T_true);
  return out;
}

void expectRecovered(const Outcome& o, unsigned seed, double max_translation_error) {
  std::cout << "[ measured ] seed " << seed << ": translation error " << o.translation_error * 1e3
            << " mm, rotation error " << o.rotation_error_deg << " deg, outliers flagged "
            << o.outliers_flagged << ", inliers kept " << o.inliers_kept << "\n";
  EXPECT_LT(o.translation_error, max_translation_error) << "seed " << seed;
  EXPECT_LT(o.rotation_error_deg, 0.05) << "seed " << seed;
  EXPECT_GE(o.outliers_flagged, 0.95) << "seed " << seed;
  EXPECT_GE(o.inliers_kept, 0.95) << "seed " << seed;
  EXPECT_EQ(o.returned, o.counted) << "the return value must count the inlier flags";
}

TEST(PoseOptimizer, RecoversThePoseAndFlagsThirtyPercentOutliers) {
  // Measured: 0.72 mm, 0.017 deg, every outlier flagged, 99.5 % of inliers kept.
  const Eigen::Isometry3d T_true = truePose();
  const Scene scene = makeScene(makeCamera(), T_true, 300, 0.30, 42);
  ASSERT_GT(scene.outliers, 70);
  ASSERT_LT(scene.outliers, 110);
  expectRecovered(solve(scene, T_true, 42), 42, 1e-3);
}

TEST(PoseOptimizer, RecoversThePoseOverSeveralSeeds) {
  // Measured over seeds 1-300: translation median 0.52 mm, p95 0.92 mm, max 1.33 mm (the
  // optimum for 0.5 px noise: more iterations or rounds change nothing); rotation max 0.043
  // deg. Seeds 1-6 (this build): max 0.83 mm, mean 0.46 mm.
  const Eigen::Isometry3d T_true = truePose();
  double sum = 0;
  const unsigned seeds = 6;
  for (unsigned seed = 1; seed <= seeds; ++seed) {
    const Scene scene = makeScene(makeCamera(), T_true, 300, 0.30, seed);
    const Outcome o = solve(scene, T_true, seed);
    expectRecovered(o, seed, 1.5e-3);
    sum += o.translation_error;
  }
  EXPECT_LT(sum / seeds, 0.7e-3);
}

TEST(PoseOptimizer, OutliersCostNothingAgainstAnInlierOnlySolve) {
  // The same scene without its outliers: the robust solve must reach the same pose, so the
  // bounds above are the noise floor, not the outliers' pull.
  const Eigen::Isometry3d T_true = truePose();
  for (unsigned seed : {5u, 42u}) {
    const Scene scene = makeScene(makeCamera(), T_true, 300, 0.30, seed);
    Scene clean;
    for (size_t i = 0; i < scene.observations.size(); ++i) {
      if (scene.is_outlier[i]) continue;
      clean.observations.push_back(scene.observations[i]);
      clean.is_outlier.push_back(false);
    }
    clean.outliers = 0;
    const Outcome robust = solve(scene, T_true, seed);
    const Outcome oracle = solve(clean, T_true, seed);
    std::cout << "[ measured ] seed " << seed << ": with outliers "
              << robust.translation_error * 1e3 << " mm, inliers only "
              << oracle.translation_error * 1e3 << " mm\n";
    EXPECT_LT(std::abs(robust.translation_error - oracle.translation_error), 0.2e-3);
    EXPECT_LT(std::abs(robust.rotation_error_deg - oracle.rotation_error_deg), 0.01);
  }
}

TEST(PoseOptimizer, StartingPoseMatters) {
  // Control: without optimisation the start is off by the perturbation, so the bounds above
  // are not met trivially.
  const Eigen::Isometry3d T_true = truePose();
  const Eigen::Isometry3d start = perturbed(T_true, 42);
  EXPECT_GT(translationError(start, T_true), 0.02);
  EXPECT_NEAR(rotationErrorDeg(start, T_true), 3.0, 1e-9);
}

TEST(PoseOptimizer, ReprojectionOnlyWithoutDepth) {
  // Monocular observations only: the pose is still determined, less tightly.
  const Eigen::Isometry3d T_true = truePose();
  Scene scene = makeScene(makeCamera(), T_true, 300, 0.0, 7);
  for (auto& o : scene.observations) o.depth = o.depth_sigma = 0.0;
  const Outcome o = solve(scene, T_true, 7);
  std::cout << "[ measured ] no depth: translation error " << o.translation_error * 1e3
            << " mm, rotation error " << o.rotation_error_deg << " deg\n";
  EXPECT_LT(o.translation_error, 5e-3);
  EXPECT_LT(o.rotation_error_deg, 0.1);
  EXPECT_GE(o.inliers_kept, 0.95);
}

TEST(PoseOptimizer, NoObservationsLeavesThePose) {
  const PoseOptimizer optimizer(makeCamera(), PoseOptimizerParams());
  const Eigen::Isometry3d start = truePose();
  Eigen::Isometry3d T = start;
  std::vector<bool> inlier(5, true);  // stale content must be cleared
  EXPECT_EQ(optimizer.optimize({}, T, inlier), 0);
  EXPECT_TRUE(inlier.empty());
  EXPECT_EQ((T.matrix() - start.matrix()).cwiseAbs().maxCoeff(), 0.0);
}

// Landmarks behind the camera at the true pose (z < 0 in the camera), observed at plausible
// pixels: what a wrong match after a fast turn gives. z = 0 puts one at the optical centre.
void addLandmarksBehind(Scene& scene, const Eigen::Isometry3d& T_cw,
                        const std::vector<double>& depths) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u_dist(50.0, 590.0), v_dist(50.0, 430.0);
  for (size_t i = 0; i < depths.size(); ++i) {
    PointObservation o;
    o.world = T_cw.inverse() * Eigen::Vector3d(0.1 * (i % 5) - 0.2, 0.05 * (i % 3), depths[i]);
    o.pixel = {u_dist(rng), v_dist(rng)};
    if (i % 2) {
      o.depth = 1.5;
      o.depth_sigma = 0.01;
    }
    scene.observations.push_back(o);
    scene.is_outlier.push_back(true);
    ++scene.outliers;
  }
}

TEST(PoseOptimizer, PointsBehindTheCameraGiveNoNan) {
  const Eigen::Isometry3d T_true = truePose();
  Scene scene = makeScene(makeCamera(), T_true, 200, 0.0, 3);
  std::vector<double> depths;
  for (int i = 0; i < 20; ++i) depths.push_back(-0.5 - 0.1 * i);
  depths.push_back(0.0);
  addLandmarksBehind(scene, T_true, depths);
  const Outcome o = solve(scene, T_true, 3);
  EXPECT_TRUE(std::isfinite(o.translation_error));
  EXPECT_TRUE(std::isfinite(o.rotation_error_deg));

  // Only landmarks behind the camera: nothing fits, and the pose stays finite.
  const std::vector<PointObservation> behind(scene.observations.end() - depths.size(),
                                             scene.observations.end());
  const PoseOptimizer optimizer(makeCamera(), PoseOptimizerParams());
  Eigen::Isometry3d T = perturbed(T_true, 3);
  std::vector<bool> inlier;
  EXPECT_EQ(optimizer.optimize(behind, T, inlier), 0);
  EXPECT_TRUE(T.matrix().allFinite()) << T.matrix();
}

TEST(PoseOptimizer, LandmarksBehindTheCameraDoNotDragThePose) {
  // One (or three) of ~200 observations is a landmark 2.2-2.4 m behind the camera. Random-pixel
  // outliers at 30 % are absorbed (tests above); these must be too. Measured with the library
  // at the time of writing: 1 landmark: 95 mm, 2.9 deg, 1 % of inliers kept; 3 landmarks:
  // 2.5 m, 45.6 deg, none kept.
  const Eigen::Isometry3d T_true = truePose();
  for (const std::vector<double>& depths : {std::vector<double>{-2.2}, {-2.2, -2.3, -2.4}}) {
    Scene scene = makeScene(makeCamera(), T_true, 200, 0.0, 3);
    addLandmarksBehind(scene, T_true, depths);
    const Outcome o = solve(scene, T_true, 3);
    std::cout << "[ measured ] " << depths.size() << " landmark(s) behind: translation error "
              << o.translation_error * 1e3 << " mm, rotation error " << o.rotation_error_deg
              << " deg, inliers kept " << o.inliers_kept << "\n";
    EXPECT_LT(o.translation_error, 1e-3) << depths.size() << " behind";
    EXPECT_LT(o.rotation_error_deg, 0.05) << depths.size() << " behind";
    EXPECT_EQ(o.outliers_flagged, 1.0) << "a landmark behind the camera cannot be an inlier";
    EXPECT_GE(o.inliers_kept, 0.95) << depths.size() << " behind";
  }
}

// The classification shares the cost's behind-camera threshold: a landmark nearer than
// PointResidual::kMinDepth, whose cost is a constant without gradient, is no inlier (it was one
// when its pixel fitted: the classification projected anything beyond 1e-6 m).
TEST(PoseOptimizer, LandmarkNearerThanTheMinimumDepthIsNoInlier) {
  const PinholeCamera camera = makeCamera();
  const Eigen::Isometry3d T = truePose();
  Scene scene = makeScene(camera, T, 50, 0.0, 5);
  for (PointObservation& o : scene.observations) {  // exact, so the solve stays at T
    const Eigen::Vector3d p_c = T * o.world;
    o.pixel = camera.project(p_c);
    if (o.depth > 0.0) o.depth = p_c.z();
  }
  PointObservation near;
  near.world = T.inverse() * Eigen::Vector3d(0.0, 0.0, 0.5 * PointResidual::kMinDepth);
  near.pixel = {camera.cx, camera.cy};
  scene.observations.push_back(near);
  const PoseOptimizer optimizer(camera, PoseOptimizerParams());
  Eigen::Isometry3d solved = T;
  std::vector<bool> inlier;
  EXPECT_EQ(optimizer.optimize(scene.observations, solved, inlier), 50);
  EXPECT_FALSE(inlier.back());
}

// The chi-square table: the depth residual's degree of freedom takes the 2-DoF bound to the
// 3-DoF one.
TEST(ChiSquare, DepthDegreeOfFreedomJoinsTheTwoBounds) {
  EXPECT_NEAR(withDepthDof(kChiSquare95TwoDof), kChiSquare95ThreeDof, 1e-12);
  EXPECT_DOUBLE_EQ(PoseOptimizerParams().chi2_pixel, kChiSquare95TwoDof);
  EXPECT_DOUBLE_EQ(PoseOptimizerParams().chi2_depth, kChiSquare95ThreeDof);
}

// What SolverOptions does not set must be Ceres' own default, so that moving the settings into
// options changed no solve; and every setting reaches Ceres.
TEST(SolverOptions, DefaultsAreCeresDefaultsAndEverySettingReachesCeres) {
  const ceres::Solver::Options ceres_defaults;
  const SolverOptions defaults;
  EXPECT_EQ(defaults.max_iterations, ceres_defaults.max_num_iterations);
  EXPECT_EQ(defaults.function_tolerance, ceres_defaults.function_tolerance);
  EXPECT_EQ(defaults.gradient_tolerance, ceres_defaults.gradient_tolerance);
  EXPECT_EQ(defaults.parameter_tolerance, ceres_defaults.parameter_tolerance);

  SolverOptions o;
  o.linear_solver = LinearSolver::kSparseNormalCholesky;
  o.max_iterations = 7;
  o.function_tolerance = 1e-2;
  o.gradient_tolerance = 1e-3;
  o.parameter_tolerance = 1e-4;
  o.num_threads = 2;
  const ceres::Solver::Options c = toCeres(o);
  EXPECT_EQ(c.linear_solver_type, ceres::SPARSE_NORMAL_CHOLESKY);
  EXPECT_EQ(c.max_num_iterations, 7);
  EXPECT_EQ(c.function_tolerance, 1e-2);
  EXPECT_EQ(c.gradient_tolerance, 1e-3);
  EXPECT_EQ(c.parameter_tolerance, 1e-4);
  EXPECT_EQ(c.num_threads, 2);
  EXPECT_EQ(c.logging_type, ceres::SILENT);
  EXPECT_EQ(toCeres(poseSolverDefaults()).linear_solver_type, ceres::DENSE_QR);
  o.linear_solver = LinearSolver::kSparseSchur;
  EXPECT_EQ(toCeres(o).linear_solver_type, ceres::SPARSE_SCHUR);
  o.linear_solver = LinearSolver::kDenseSchur;
  EXPECT_EQ(toCeres(o).linear_solver_type, ceres::DENSE_SCHUR);
}

}  // namespace
}  // namespace ply_slam
