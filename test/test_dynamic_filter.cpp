// The Delaunay topology check and the label dynamic degree (PAPER.md §3.2) on scenes with a
// known moving object: a static background and a cluster that moves between the frames.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <iostream>
#include <random>

#include "ply_slam/dynamic/dynamic_feature_filter.h"
#include "ply_slam/synth/synthetic_sequence.h"

namespace ply_slam {
namespace {

struct Scene {
  std::vector<FeatureCorrespondence> features;
  std::vector<int> instance;  // 1 = the object, 2 = a static object, 0 = background
  std::vector<bool> moving;
};

// Background points 2-4 m away and an object of 60 points around (0.3, 0, 1.5) m, which moves
// by `object_motion` between the frames; the camera itself moves by a small rigid motion.
Scene makeScene(const Eigen::Vector3d& object_motion, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::normal_distribution<double> noise(0.0, 0.002);
  const PinholeCamera cam = syntheticCamera();
  Eigen::Isometry3d motion = Eigen::Isometry3d::Identity();  // previous -> current camera
  motion.linear() = Eigen::AngleAxisd(0.03, Eigen::Vector3d(0.2, 1.0, 0.1).normalized()).matrix();
  motion.translation() = Eigen::Vector3d(0.02, -0.01, 0.03);
  Scene s;
  auto add = [&](const Eigen::Vector3d& p_prev, int id, bool moves) {
    Eigen::Vector3d p_cur = motion * (p_prev + (moves ? object_motion : Eigen::Vector3d::Zero()));
    FeatureCorrespondence f;
    f.previous = p_prev + Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
    f.current = p_cur + Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
    f.pixel = cam.project(p_cur);
    if (!cam.inImage(f.pixel, 5)) return;
    s.features.push_back(f);
    s.instance.push_back(id);
    s.moving.push_back(moves);
  };
  for (int i = 0; i < 400; ++i) add({1.6 * u(rng), 1.2 * u(rng), 3.0 + u(rng)}, 0, false);
  for (int i = 0; i < 60; ++i)
    add(Eigen::Vector3d(0.3, 0.0, 1.5) + 0.15 * Eigen::Vector3d(u(rng), 2 * u(rng), 0.3 * u(rng)),
        1, true);
  for (int i = 0; i < 40; ++i)
    add(Eigen::Vector3d(-0.5, 0.3, 2.0) + 0.15 * Eigen::Vector3d(u(rng), u(rng), 0.3 * u(rng)), 2,
        false);
  return s;
}

PinholeCamera noisyCamera() {
  PinholeCamera cam = syntheticCamera();
  cam.depth_noise.alpha = 2.5e-5;
  cam.depth_noise.gamma = 1e-5;
  return cam;
}

TEST(DelaunayConsistency, MovingObjectGetsHighWeightsStaticLow) {
  // 0.16 m between the compared frames: a person walking 1.2 m/s, frames 4 apart.
  const Scene s = makeScene({0.15, 0.0, 0.05}, 1);
  const DelaunayConsistency check(noisyCamera(), {});
  const auto w = check.weights(s.features, 640, 480);
  double moving = 0;
  int n_moving = 0, n_still = 0, still_in_dp = 0;
  for (size_t i = 0; i < w.size(); ++i) {
    if (s.moving[i]) {
      moving += w[i];
      ++n_moving;
    } else {
      ++n_still;
      still_in_dp += w[i] > 0.5;
    }
  }
  ASSERT_GT(n_moving, 30);
  // Inside the object most edges stay rigid; its border edges to the background break, and a
  // broken edge blames both ends, so background neighbours of the object get weight too.
  // The dynamic-rejection target (docs/RESULTS.md) allows at most 10 % of static features dropped.
  std::cout << "[ measured ] mean weight on the object " << moving / n_moving << ", static in DP "
            << still_in_dp << " of " << n_still << "\n";
  EXPECT_GT(moving / n_moving, 0.25);
  EXPECT_LE(still_in_dp, 0.10 * n_still);
}

TEST(DelaunayConsistency, StaticSceneIsConsistent) {
  const Scene s = makeScene(Eigen::Vector3d::Zero(), 2);
  const auto w = DelaunayConsistency(noisyCamera(), {}).weights(s.features, 640, 480);
  int high = 0;
  for (double x : w) high += x > 0.5;
  EXPECT_EQ(high, 0);
}

// A corridor 2 m wide seen along its length, every point static. The walls slope steeply in
// the image (5 cm of depth per pixel at 5 m), so a keypoint found 0.7 px off reads its depth a
// few centimetres off, along the ray, far beyond an exact sensor's depth noise.
// Depth of the corridor (walls x = +-1 m, floor y = 1 m, ceiling y = -1.4 m, previous camera's
// frame) along the ray of pixel (u, v) of a camera at T_prev_cam; 0 beyond 12 m.
double corridorDepth(const PinholeCamera& cam, const Eigen::Isometry3d& T_prev_cam, double u,
                     double v) {
  const Eigen::Vector3d ray((u - cam.cx) / cam.fx, (v - cam.cy) / cam.fy, 1.0);
  const Eigen::Vector3d o = T_prev_cam.translation(), d = T_prev_cam.linear() * ray;
  double t = 12.0;
  for (const auto& [axis, at] : {std::pair{0, 1.0}, {0, -1.0}, {1, 1.0}, {1, -1.4}})
    if (std::abs(d[axis]) > 1e-9) {
      const double hit = (at - o[axis]) / d[axis];
      if (hit > 0.0) t = std::min(t, hit);
    }
  return t < 12.0 ? t : 0.0;  // ray z = 1 in the camera: t is the depth
}

// The synthetic scenes' camera with their exact depth (quantised to 0.2 mm).
PinholeCamera exactDepthCamera() {
  PinholeCamera cam = syntheticCamera();
  cam.depth_noise.alpha = 3e-7;
  cam.depth_noise.gamma = 3.3e-9;
  return cam;
}

std::vector<FeatureCorrespondence> corridorView(bool with_slopes, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> pixel_u(5.0, 634.0), pixel_v(5.0, 474.0);
  std::normal_distribution<double> keypoint_error(0.0, 0.7);
  const PinholeCamera cam = exactDepthCamera();
  Eigen::Isometry3d T_prev_cur = Eigen::Isometry3d::Identity();  // walking forward, turning
  T_prev_cur.linear() = Eigen::AngleAxisd(0.02, Eigen::Vector3d::UnitY()).matrix();
  T_prev_cur.translation() = Eigen::Vector3d(0.01, 0.0, 0.12);
  const Eigen::Isometry3d identity = Eigen::Isometry3d::Identity();
  // The point the camera at T measures at a keypoint found at (u, v), and the slope there.
  auto measure = [&](const Eigen::Isometry3d& T, const Eigen::Vector2d& uv, Eigen::Vector3d& p,
                     Eigen::Vector2d& slope) {
    const double z = corridorDepth(cam, T, uv.x(), uv.y());
    p = cam.backProject(uv, z);
    slope.x() =
        (corridorDepth(cam, T, uv.x() + 1, uv.y()) - corridorDepth(cam, T, uv.x() - 1, uv.y())) / 2;
    slope.y() =
        (corridorDepth(cam, T, uv.x(), uv.y() + 1) - corridorDepth(cam, T, uv.x(), uv.y() - 1)) / 2;
    if (!with_slopes) slope.setZero();
    return z > 0.0;
  };
  std::vector<FeatureCorrespondence> view;
  while (view.size() < 500) {
    // A static point of the corridor, seen in the previous frame and in the current one.
    const Eigen::Vector2d uv_prev(pixel_u(rng), pixel_v(rng));
    const double z = corridorDepth(cam, identity, uv_prev.x(), uv_prev.y());
    if (z <= 0.5) continue;
    const Eigen::Vector3d point = cam.backProject(uv_prev, z);
    const Eigen::Vector3d in_current = T_prev_cur.inverse() * point;
    const Eigen::Vector2d uv_cur = cam.project(in_current);
    if (in_current.z() <= 0.5 || !cam.inImage(uv_cur, 5)) continue;
    // Each frame finds the keypoint a little off, and reads the depth where it found it.
    FeatureCorrespondence f;
    const Eigen::Vector2d error_prev(keypoint_error(rng), keypoint_error(rng));
    const Eigen::Vector2d error_cur(keypoint_error(rng), keypoint_error(rng));
    if (!measure(identity, uv_prev + error_prev, f.previous, f.slope_previous)) continue;
    if (!measure(T_prev_cur, uv_cur + error_cur, f.current, f.slope_current)) continue;
    f.pixel = uv_cur + error_cur;
    view.push_back(f);
  }
  return view;
}

int flaggedInCorridor(bool with_slopes) {
  const auto w =
      DelaunayConsistency(exactDepthCamera(), {}).weights(corridorView(with_slopes, 7), 640, 480);
  return static_cast<int>(std::count_if(w.begin(), w.end(), [](double x) { return x > 0.5; }));
}

TEST(DelaunayConsistency, CorridorWallsSeenAlongAreStatic) {
  const int without = flaggedInCorridor(false), with = flaggedInCorridor(true);
  std::cout << "[ measured ] static corridor features flagged: " << without
            << " of 500 without the depth slopes, " << with << " with them\n";
  EXPECT_GT(without, 50);  // the scene does need the slopes
  EXPECT_LE(with, 10);     // at most 2 %
}

TEST(DynamicFeatureFilter, ActiveInstanceDroppedWholePassiveAndStaticKept) {
  const Scene s = makeScene({0.15, 0.0, 0.05}, 3);
  const DynamicFeatureFilter filter(noisyCamera(), {});
  // The moving object labelled person (active): all of its features go.
  auto d = filter.decide(s.features, s.instance,
                         {{1, ClassMotion::kActive}, {2, ClassMotion::kPassive}}, 640, 480);
  ASSERT_TRUE(d.dynamic_instances.count(1)) << "r_d " << d.degree[1];
  EXPECT_TRUE(d.measured.count(1));
  EXPECT_FALSE(d.dynamic_instances.count(2));
  int static_dropped = 0, static_total = 0;
  for (size_t i = 0; i < s.features.size(); ++i) {
    if (s.moving[i]) {
      EXPECT_TRUE(d.dynamic[i]) << "feature " << i << " on the moving person";
    } else {
      ++static_total;
      static_dropped += d.dynamic[i];
    }
  }
  EXPECT_LE(static_dropped, 0.05 * static_total);

  // The same object labelled as a static class is never dropped as a whole (its features still
  // go one by one, on their own weights, as it does move).
  d = filter.decide(s.features, s.instance, {{1, ClassMotion::kStatic}}, 640, 480);
  EXPECT_FALSE(d.dynamic_instances.count(1));
}

// The label rules: an instance is dynamic as a whole when its dynamic degree r_d exceeds
// Th_min (active class) or Th_max (passive class); an active instance without enough matched
// features to judge is presumed dynamic, a passive one is not.
TEST(DynamicFeatureFilter, LabelRulesFollowTheThresholds) {
  Scene s = makeScene({0.15, 0.0, 0.05}, 5);
  // Instance 3: half the moving object and as many static background features.
  int moving = 0, still = 0;
  for (size_t i = 0; i < s.features.size(); ++i) {
    if (s.moving[i] && moving < 20) s.instance[i] = 3, ++moving;
    if (!s.moving[i] && s.instance[i] == 0 && still < 20) s.instance[i] = 3, ++still;
  }
  const auto degree = DynamicFeatureFilter(noisyCamera(), {})
                          .decide(s.features, s.instance, {{3, ClassMotion::kActive}}, 640, 480)
                          .degree.at(3);
  ASSERT_GT(degree, 0.3);
  ASSERT_LT(degree, 0.7);
  auto judged = [&](ClassMotion kind, double active, double passive) {
    DynamicFilterOptions p;
    p.active_degree = active;
    p.passive_degree = passive;
    return DynamicFeatureFilter(noisyCamera(), p)
               .decide(s.features, s.instance, {{3, kind}}, 640, 480)
               .dynamic_instances.count(3) > 0;
  };
  EXPECT_TRUE(judged(ClassMotion::kActive, degree - 0.05, 0.95));
  EXPECT_FALSE(judged(ClassMotion::kActive, degree + 0.05, 0.95));
  EXPECT_TRUE(judged(ClassMotion::kPassive, 0.05, degree - 0.05));
  EXPECT_FALSE(judged(ClassMotion::kPassive, 0.05, degree + 0.05));
  EXPECT_FALSE(judged(ClassMotion::kStatic, 0.0, 0.0));

  // Instances no feature lies on: the person is presumed moving, the chair is not.
  const auto d = DynamicFeatureFilter(noisyCamera(), {})
                     .decide(s.features, s.instance,
                             {{8, ClassMotion::kActive}, {9, ClassMotion::kPassive}}, 640, 480);
  EXPECT_TRUE(d.dynamic_instances.count(8));
  EXPECT_FALSE(d.dynamic_instances.count(9));
  // Presumed, not measured: nothing showed it moving.
  EXPECT_FALSE(d.measured.count(8));
}

TEST(DynamicFeatureFilter, StaticSceneKeepsEverything) {
  const Scene s = makeScene(Eigen::Vector3d::Zero(), 4);
  const auto d = DynamicFeatureFilter(noisyCamera(), {})
                     .decide(s.features, s.instance,
                             {{1, ClassMotion::kActive}, {2, ClassMotion::kPassive}}, 640, 480);
  EXPECT_TRUE(d.dynamic_instances.empty());
  int dropped = 0;
  for (bool x : d.dynamic) dropped += x;
  EXPECT_EQ(dropped, 0);
}

// A person a metre away covering most of the image (a torso: 300 features moving rigidly by
// 10 cm between the frames) in front of a background with 60 features 3 m away.
struct CrowdedScene {
  std::vector<FeatureCorrespondence> features;
  std::vector<bool> on_person;
  Eigen::Isometry3d camera_motion = Eigen::Isometry3d::Identity();  // previous -> current
};

CrowdedScene makeCrowdedScene(unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::normal_distribution<double> noise(0.0, 0.002);
  const PinholeCamera cam = syntheticCamera();
  CrowdedScene s;
  s.camera_motion.linear() = Eigen::AngleAxisd(0.01, Eigen::Vector3d::UnitY()).matrix();
  s.camera_motion.translation() = Eigen::Vector3d(0.01, 0.0, 0.005);
  auto add = [&](const Eigen::Vector3d& p_prev, bool person) {
    const Eigen::Vector3d walked =
        person ? Eigen::Vector3d(0.1, 0.0, 0.02) : Eigen::Vector3d::Zero();
    FeatureCorrespondence f;
    f.previous = p_prev + Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
    f.current =
        s.camera_motion * (p_prev + walked) + Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
    f.pixel = cam.project(s.camera_motion * (p_prev + walked));
    if (!cam.inImage(f.pixel, 5)) return;
    s.features.push_back(f);
    s.on_person.push_back(person);
  };
  for (int i = 0; i < 300; ++i) add({0.5 * u(rng), 0.4 * u(rng), 1.0 + 0.05 * u(rng)}, true);
  for (int i = 0; i < 60; ++i) {
    // Background along the image's left and right edges, beside the person.
    const double x = (i % 2 ? 1.0 : -1.0) * (1.3 + 0.3 * u(rng));
    add({x, 1.1 * u(rng), 3.0 + 0.3 * u(rng)}, false);
  }
  return s;
}

// Shares of the person's features with weight > 0.5 and of the background's.
std::pair<double, double> flaggedShares(const CrowdedScene& s, const std::vector<double>& w) {
  int person = 0, background = 0, person_flagged = 0, background_flagged = 0;
  for (size_t i = 0; i < w.size(); ++i) {
    (s.on_person[i] ? person : background) += 1;
    (s.on_person[i] ? person_flagged : background_flagged) += w[i] > 0.5;
  }
  return {static_cast<double>(person_flagged) / person,
          static_cast<double>(background_flagged) / background};
}

TEST(DelaunayConsistency, PersonCoveringTheImageIsNotTakenForTheStaticScene) {
  const CrowdedScene s = makeCrowdedScene(3);
  const DelaunayConsistency check(noisyCamera(), {});
  // Nothing but the features: the torso's edges to the background are most of the edges, so
  // the noise scale and the rigid bodies take it in with the scene, and the person is kept
  // (the failure among people at 1 m).
  const auto blind = flaggedShares(s, check.weights(s.features, 640, 480));
  EXPECT_LT(blind.first, 0.5);

  // The camera's predicted motion, 1 cm and 0.2 deg off the true one, picks the background.
  Eigen::Isometry3d predicted = s.camera_motion;
  predicted.translation() += Eigen::Vector3d(0.007, -0.005, 0.005);
  predicted.linear() =
      Eigen::AngleAxisd(0.0035, Eigen::Vector3d::UnitX()).matrix() * predicted.linear();
  StaticPrior by_prediction;
  by_prediction.predicted_motion = &predicted;
  const auto [person_pred, background_pred] =
      flaggedShares(s, check.weights(s.features, 640, 480, by_prediction));
  EXPECT_GT(person_pred, 0.9);
  EXPECT_LT(background_pred, 0.1);

  // No prediction (just after a loss), but the person's instance label.
  StaticPrior by_label;
  by_label.on_moving_class = &s.on_person;
  const auto [person_label, background_label] =
      flaggedShares(s, check.weights(s.features, 640, 480, by_label));
  EXPECT_GT(person_label, 0.9);
  EXPECT_LT(background_label, 0.1);
}

// A small body (a hand, a face at the image's edge): three features that moved 10 cm together,
// the others wrong matches. Whichever three they are, the body's own motion is found: every
// triple a body of up to six has is tried (C(6, 3) = 20 < kBodyRansacRounds), none with a
// repeated feature, which leaves the motion undetermined and scored the identity instead.
TEST(DelaunayConsistency, SmallBodyMovedApartWhereverItsRigidCoreIs) {
  const DelaunayConsistency check(noisyCamera(), {});
  DelaunayConsistency::StaticFit fit;  // the camera stood still
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-0.3, 0.3);
  const Eigen::Vector3d walked(0.1, 0.0, 0.0);
  int placements = 0, found = 0;
  for (size_t n = 3; n <= 6; ++n)
    for (unsigned core = 0; core < (1u << n); ++core) {
      if (__builtin_popcount(core) != 3) continue;
      std::vector<FeatureCorrespondence> body;
      for (size_t i = 0; i < n; ++i) {
        FeatureCorrespondence f;
        f.previous = Eigen::Vector3d(u(rng), u(rng), 1.5 + u(rng));
        // Wrong matches land anywhere within 30 cm; the core moves as one.
        f.current = (core >> i & 1u) ? Eigen::Vector3d(f.previous + walked)
                                     : Eigen::Vector3d(u(rng), u(rng), 1.5 + u(rng));
        body.push_back(f);
      }
      ++placements;
      found += check.movedApart(body, fit);
    }
  EXPECT_EQ(placements, 1 + 4 + 10 + 20);
  EXPECT_EQ(found, placements);
}

}  // namespace
}  // namespace ply_slam
