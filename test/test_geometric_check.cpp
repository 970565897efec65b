// Geometric check of loop candidates: a known rigid motion between two keyframes with noisy
// matches and 40 % outliers must be recovered and the outliers rejected; unrelated points must
// not pass; the 3D bound must follow the depth noise.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "ply_slam/loop/geometric_check.h"
#include "pose_test_helpers.h"

namespace ply_slam {
namespace {

using test::makeCamera;
using test::rotationErrorDeg;
using test::translationError;
using test::truePose;  // 20 deg about a tilted axis, (0.3, -0.1, 0.2) m

// A point in front of the candidate camera that both cameras see.
Eigen::Vector3d visiblePoint(const PinholeCamera& camera, const Eigen::Isometry3d& T_qc,
                             std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  while (true) {
    const double z = 1.0 + 3.0 * u(rng);
    const Eigen::Vector3d p =
        camera.backProject({camera.width * u(rng), camera.height * u(rng)}, z);
    const Eigen::Vector3d q = T_qc * p;
    if (q.z() > 0.5 && camera.inImage(camera.project(q), 5.0)) return p;
  }
}

struct Scene {
  std::vector<PutativeMatch> matches;
  std::vector<bool> outlier;
};

// The point moved along its viewing ray by a depth error drawn from the sensor model.
Eigen::Vector3d withDepthNoise(const Eigen::Vector3d& p, std::mt19937& rng) {
  std::normal_distribution<double> sigmas(0.0, 1.0);
  const double z = p.z() + sigmas(rng) * std::sqrt(DepthNoiseModel().variance(p.z()));
  return p * (z / p.z());
}

// n matches, a share of them outliers (the query point displaced by 0.3..1.5 m, observed where
// that wrong point projects). 0.5 mm noise on every 3D point (the < 1 mm pose bound leaves no
// room for real depth noise), 0.5 px on every observation.
// With sensor_noise the Kinect depth model's error is added on top.
Scene makeScene(int n, double outlier_share, unsigned seed, bool sensor_noise = false,
                const Eigen::Isometry3d& T_qc = truePose()) {
  const PinholeCamera camera = makeCamera();
  std::mt19937 rng(seed);
  std::normal_distribution<double> mm(0.0, 0.0005), px(0.0, 0.5);
  std::uniform_real_distribution<double> u(-1.0, 1.0), len(0.3, 1.5);
  Scene scene;
  for (int k = 0; k < n; ++k) {
    const Eigen::Vector3d p_c = visiblePoint(camera, T_qc, rng);
    Eigen::Vector3d p_q = T_qc * p_c;
    const bool outlier = k < outlier_share * n;
    if (outlier) p_q += len(rng) * Eigen::Vector3d(u(rng), u(rng), 0.3 * u(rng)).normalized();
    PutativeMatch m;
    m.p_candidate = p_c + Eigen::Vector3d(mm(rng), mm(rng), mm(rng));
    m.p_query = p_q + Eigen::Vector3d(mm(rng), mm(rng), mm(rng));
    m.uv_candidate = camera.project(p_c) + Eigen::Vector2d(px(rng), px(rng));
    m.uv_query = camera.project(p_q) + Eigen::Vector2d(px(rng), px(rng));
    if (sensor_noise) {
      m.p_candidate = withDepthNoise(m.p_candidate, rng);
      m.p_query = withDepthNoise(m.p_query, rng);
    }
    scene.matches.push_back(m);
    scene.outlier.push_back(outlier);
  }
  return scene;
}

// The check without the revisit bound: truePose() (0.37 m, 20 deg) is farther than a revisit.
LoopOptions anyMotion() {
  LoopOptions o;
  o.max_revisit_distance_m = 1e9;
  o.max_revisit_angle_deg = 180.0;
  return o;
}

TEST(GeometricCheck, RecoversAKnownMotionThroughOutliers) {
  const Scene scene = makeScene(100, 0.4, 7);
  const GeometricCheckResult r = checkLoopGeometry(scene.matches, makeCamera(), anyMotion());
  ASSERT_TRUE(r.accepted);
  EXPECT_LT(translationError(r.T_query_candidate, truePose()), 0.001);
  EXPECT_LT(rotationErrorDeg(r.T_query_candidate, truePose()), 0.1);
  int true_inliers = 0;
  for (size_t k : r.inliers) {
    EXPECT_FALSE(scene.outlier[k]) << "outlier " << k << " taken as an inlier";
    ++true_inliers;
  }
  EXPECT_GE(true_inliers, 57);  // of the 60 true matches
  EXPECT_GE(r.inliers_3d, 57);
  EXPECT_LE(r.inliers_3d, 60);
}

TEST(GeometricCheck, AcceptsUnderSensorDepthNoise) {
  // sigma_Z 6..20 mm over 1..4 m: the depth-aware bound keeps the true matches (3 sigma: ~99 %),
  // the pose is good to centimetres, the displaced outliers (>= 0.3 m) stay out.
  const Scene scene = makeScene(100, 0.4, 13, true);
  const GeometricCheckResult r = checkLoopGeometry(scene.matches, makeCamera(), anyMotion());
  ASSERT_TRUE(r.accepted);
  EXPECT_LT(translationError(r.T_query_candidate, truePose()), 0.02);
  EXPECT_LT(rotationErrorDeg(r.T_query_candidate, truePose()), 0.5);
  EXPECT_GE(r.inliers_3d, 55);
  for (size_t k : r.inliers) EXPECT_FALSE(scene.outlier[k]);
}

TEST(GeometricCheck, IsDeterministic) {
  const Scene scene = makeScene(80, 0.4, 11);
  const GeometricCheckResult a = checkLoopGeometry(scene.matches, makeCamera(), anyMotion());
  const GeometricCheckResult b = checkLoopGeometry(scene.matches, makeCamera(), anyMotion());
  EXPECT_EQ(a.inliers, b.inliers);
  EXPECT_TRUE(a.T_query_candidate.isApprox(b.T_query_candidate, 0.0));
}

TEST(GeometricCheck, RejectsUnrelatedPoints) {
  // Query and candidate points drawn independently: no motion explains more than a handful.
  const PinholeCamera camera = makeCamera();
  std::mt19937 rng(3);
  std::vector<PutativeMatch> matches;
  for (int k = 0; k < 100; ++k) {
    PutativeMatch m;
    m.p_candidate = visiblePoint(camera, Eigen::Isometry3d::Identity(), rng);
    m.p_query = visiblePoint(camera, Eigen::Isometry3d::Identity(), rng);
    m.uv_candidate = camera.project(m.p_candidate);
    m.uv_query = camera.project(m.p_query);
    matches.push_back(m);
  }
  const GeometricCheckResult r = checkLoopGeometry(matches, camera, anyMotion());
  EXPECT_FALSE(r.accepted);
  EXPECT_LT(r.inliers_3d, LoopOptions().min_inliers_3d);
}

TEST(GeometricCheck, TooFewMatchesAreRejected) {
  const Scene scene = makeScene(10, 0.0, 5);  // all correct, but fewer than min_inliers_3d
  const GeometricCheckResult r = checkLoopGeometry(scene.matches, makeCamera(), anyMotion());
  EXPECT_FALSE(r.accepted);
  EXPECT_EQ(r.inliers_3d, 10);
  EXPECT_FALSE(checkLoopGeometry({}, makeCamera(), LoopOptions()).accepted);
}

TEST(GeometricCheck, ReprojectionBoundIsChecked) {
  // Every observation in the query image 10 px off: the 3D fit is perfect but no match
  // reprojects within 4 px, so the candidate is rejected.
  Scene scene = makeScene(60, 0.0, 9);
  for (PutativeMatch& m : scene.matches) m.uv_query.x() += 10.0;
  const GeometricCheckResult r = checkLoopGeometry(scene.matches, makeCamera(), anyMotion());
  EXPECT_GE(r.inliers_3d, 57);
  EXPECT_EQ(r.reprojection_inliers, 0);
  EXPECT_FALSE(r.accepted);
}

TEST(InlierDistance, GrowsWithDepth) {
  const LoopOptions o;  // sigma_Z^2 = 2.5e-5 Z^2 + 1e-5
  // Z = 1 m in both: 3 sqrt(2 * 3.5e-5) = 0.0251 m. Z = 5 m: 3 sqrt(2 * 6.35e-4) = 0.1069 m.
  EXPECT_NEAR(inlierDistance(1.0, 1.0, o), 3.0 * std::sqrt(7.0e-5), 1e-12);
  EXPECT_NEAR(inlierDistance(5.0, 5.0, o), 3.0 * std::sqrt(1.27e-3), 1e-12);
  LoopOptions precise;
  precise.depth_noise = {0.0, 0.0, 1e-8};  // 0.1 mm: the floor of 1 cm holds
  EXPECT_DOUBLE_EQ(inlierDistance(1.0, 1.0, precise), 0.01);
}

// A loop is a return to a place: a motion well verified but farther than max_revisit_distance_m
// or turned more than max_revisit_angle_deg is refused; a small one passes.
TEST(GeometricCheck, RefusesMotionsBeyondARevisit) {
  const Scene far = makeScene(100, 0.4, 7);  // 0.37 m, 20 deg
  const GeometricCheckResult refused = checkLoopGeometry(far.matches, makeCamera(), LoopOptions());
  EXPECT_FALSE(refused.accepted);
  EXPECT_GE(refused.inliers_3d, 57);  // verified all the same
  EXPECT_LT(translationError(refused.T_query_candidate, truePose()), 0.001);

  Eigen::Isometry3d near = Eigen::Isometry3d::Identity();
  near.linear() =
      Eigen::AngleAxisd(10.0 * M_PI / 180.0, Eigen::Vector3d(0.2, 1.0, 0.1).normalized())
          .toRotationMatrix();
  near.translation() = Eigen::Vector3d(0.15, -0.05, 0.1);  // 0.19 m
  const Scene close = makeScene(100, 0.4, 7, false, near);
  const GeometricCheckResult accepted =
      checkLoopGeometry(close.matches, makeCamera(), LoopOptions());
  EXPECT_TRUE(accepted.accepted);
  EXPECT_LT(translationError(accepted.T_query_candidate, near), 0.001);

  LoopOptions strict;
  strict.max_revisit_angle_deg = 9.0;  // the same motion, turned more than allowed
  EXPECT_FALSE(checkLoopGeometry(close.matches, makeCamera(), strict).accepted);
  strict = LoopOptions();
  strict.max_revisit_distance_m = 0.18;  // moved farther than allowed
  EXPECT_FALSE(checkLoopGeometry(close.matches, makeCamera(), strict).accepted);
}

}  // namespace
}  // namespace ply_slam
