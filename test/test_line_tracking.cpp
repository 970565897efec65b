// Lines in tracking: the pose optimiser with the endpoint-to-line
// residual of PAPER.md §3 (lines only, and with points) on synthetic scenes with a known pose
// and gross outliers, and end to end: lines.enabled false is exactly the points-only tracker.
#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/imgproc.hpp>
#include <random>
#include <vector>

#include "ply_slam/common/point_residual.h"
#include "ply_slam/eval/trajectory_metrics.h"
#include "ply_slam/features/line_extractor.h"
#include "ply_slam/features/line_fitter.h"
#include "ply_slam/features/orb_extractor.h"
#include "ply_slam/io/tum_sequence.h"
#include "ply_slam/mapping/landmark_creator.h"
#include "ply_slam/system/system.h"
#include "ply_slam/system/system_config.h"
#include "ply_slam/tracking/pose_optimizer.h"
#include "ply_slam/tracking/tracker.h"
#include "pose_test_helpers.h"
#include "shared_data.h"

namespace ply_slam {
namespace {

using namespace ::ply_slam::test;

struct LineScene {
  std::vector<LineObservation> lines;
  std::vector<bool> is_outlier;
};

// `n` 3D segments 1-4 m in front of the camera at T_cw, 0.3-1 m long in random directions.
// Each is observed as a shorter piece of itself (occluded / shifted endpoints, which the
// residual must not mind) with 0.5 px noise across the line; a fraction `outlier_ratio`
// observed as a random line instead.
LineScene makeLineScene(const PinholeCamera& camera, const Eigen::Isometry3d& T_cw, int n,
                        double outlier_ratio, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u_dist(80.0, camera.width - 80.0);
  std::uniform_real_distribution<double> v_dist(80.0, camera.height - 80.0);
  std::uniform_real_distribution<double> z_dist(1.0, 4.0);
  std::uniform_real_distribution<double> len_dist(0.3, 1.0);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::normal_distribution<double> gauss(0.0, 1.0);
  const Eigen::Isometry3d T_wc = T_cw.inverse();
  LineScene scene;
  while (static_cast<int>(scene.lines.size()) < n) {
    const Eigen::Vector3d mid = camera.backProject({u_dist(rng), v_dist(rng)}, z_dist(rng));
    const Eigen::Vector3d dir = Eigen::Vector3d(gauss(rng), gauss(rng), gauss(rng)).normalized();
    const double half = 0.5 * len_dist(rng);
    const Eigen::Vector3d a = mid - half * dir, b = mid + half * dir;
    if (a.z() < 0.5 || b.z() < 0.5) continue;
    // The observed piece: from 0-20 % to 80-100 % of the segment.
    const Eigen::Vector3d oa = a + 0.2 * unit(rng) * (b - a);
    const Eigen::Vector3d ob = b - 0.2 * unit(rng) * (b - a);
    Eigen::Vector2d ps = camera.project(oa), pe = camera.project(ob);
    if ((pe - ps).norm() < 20.0) continue;
    const Eigen::Vector2d normal = Eigen::Vector2d(-(pe - ps).y(), (pe - ps).x()).normalized();
    ps += 0.5 * gauss(rng) * normal;
    pe += 0.5 * gauss(rng) * normal;
    const bool outlier = unit(rng) < outlier_ratio;
    if (outlier) {
      ps = {u_dist(rng), v_dist(rng)};
      pe = {u_dist(rng), v_dist(rng)};
    }
    LineObservation o;
    o.start = T_wc * a;
    o.end = T_wc * b;
    const Eigen::Vector3d l = ps.homogeneous().cross(pe.homogeneous());
    o.line = l / l.head<2>().norm();
    o.pixel_sigma = 1.0;
    scene.lines.push_back(o);
    scene.is_outlier.push_back(outlier);
  }
  return scene;
}

std::vector<PointObservation> makePoints(const PinholeCamera& camera, const Eigen::Isometry3d& T_cw,
                                         int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u_dist(0.0, camera.width);
  std::uniform_real_distribution<double> v_dist(0.0, camera.height);
  std::uniform_real_distribution<double> z_dist(1.0, 4.0);
  std::normal_distribution<double> gauss(0.0, 1.0);
  std::vector<PointObservation> points;
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d p_c = camera.backProject({u_dist(rng), v_dist(rng)}, z_dist(rng));
    PointObservation o;
    o.world = T_cw.inverse() * p_c;
    o.pixel = camera.project(p_c) + 0.5 * Eigen::Vector2d(gauss(rng), gauss(rng));
    points.push_back(o);
  }
  return points;
}

TEST(LineResidual, ZeroForTheTruePoseWithShiftedEndpoints) {
  const PinholeCamera camera = makeCamera();
  const PoseOptimizer optimizer(camera, PoseOptimizerParams());
  const Eigen::Isometry3d T = truePose();
  // Noise-free: the observed piece lies on the projected line wherever its endpoints are.
  LineScene scene = makeLineScene(camera, T, 20, 0.0, 3);
  for (auto& o : scene.lines) {
    const Eigen::Vector2d ps = camera.project(T * (0.8 * o.start + 0.2 * o.end));
    const Eigen::Vector2d pe = camera.project(T * (0.1 * o.start + 0.9 * o.end));
    const Eigen::Vector3d l = ps.homogeneous().cross(pe.homogeneous());
    o.line = l / l.head<2>().norm();
    EXPECT_LT(optimizer.squaredLineError(o, T), 1e-12);
    EXPECT_GT(optimizer.squaredLineError(o, perturbed(T, 1)), 1e-2);
  }
}

// The line cost and the line classification share PointResidual's projection: an endpoint
// nearer than kMinDepth is behind the camera for both (the classification used to project
// anything beyond 1e-6 m and keep such a line as an inlier the cost ignored).
TEST(LineResidual, EndpointNearerThanTheMinimumDepthIsBehindTheCamera) {
  const PinholeCamera camera = makeCamera();
  const PoseOptimizer optimizer(camera, PoseOptimizerParams());
  LineObservation o;
  o.line = {0.0, 1.0, -camera.cy};  // the row v = cy, where both ends project
  o.end = {0.5, 0.0, 2.0};
  o.start = {0.0, 0.0, PointResidual::kMinDepth};
  EXPECT_EQ(optimizer.squaredLineError(o, Eigen::Isometry3d::Identity()), 0.0);
  o.start.z() = 0.5 * PointResidual::kMinDepth;
  EXPECT_TRUE(std::isinf(optimizer.squaredLineError(o, Eigen::Isometry3d::Identity())));
}

TEST(LineResidual, BalanceFactor) {
  EXPECT_DOUBLE_EQ(lineBalanceFactor(LineBalance::kPaper, 100), 4.0);  // 2n/50
  EXPECT_DOUBLE_EQ(lineBalanceFactor(LineBalance::kPaper, 25), 1.0);
  EXPECT_DOUBLE_EQ(lineBalanceFactor(LineBalance::kOne, 100), 1.0);
}

TEST(PoseOptimizerLines, LinesOnlyRecoverThePoseAndRejectOutliers) {
  const PinholeCamera camera = makeCamera();
  const PoseOptimizer optimizer(camera, PoseOptimizerParams());
  const Eigen::Isometry3d T_true = truePose();
  for (unsigned seed = 0; seed < 10; ++seed) {
    const LineScene scene = makeLineScene(camera, T_true, 60, 0.3, seed);
    Eigen::Isometry3d T = perturbed(T_true, seed);
    std::vector<bool> inlier, line_inlier;
    const int points = optimizer.optimize({}, scene.lines, 1.0, T, inlier, line_inlier);
    EXPECT_EQ(points, 0);
    ASSERT_EQ(line_inlier.size(), scene.lines.size());
    EXPECT_LT(translationError(T, T_true), 0.01) << "seed " << seed;
    EXPECT_LT(rotationErrorDeg(T, T_true), 0.2) << "seed " << seed;
    int flagged = 0, outliers = 0, kept = 0, inliers = 0;
    for (size_t k = 0; k < line_inlier.size(); ++k) {
      if (scene.is_outlier[k]) {
        ++outliers;
        flagged += !line_inlier[k];
      } else {
        ++inliers;
        kept += line_inlier[k];
      }
    }
    EXPECT_GE(flagged, 0.9 * outliers) << "seed " << seed;
    EXPECT_GE(kept, 0.9 * inliers) << "seed " << seed;
  }
}

TEST(PoseOptimizerLines, PointsAndLinesTogether) {
  const PinholeCamera camera = makeCamera();
  const PoseOptimizer optimizer(camera, PoseOptimizerParams());
  const Eigen::Isometry3d T_true = truePose();
  for (unsigned seed = 0; seed < 10; ++seed) {
    // Too few points for a good pose alone, lines with 30 % outliers beside them.
    const auto points = makePoints(camera, T_true, 8, seed + 50);
    const LineScene scene = makeLineScene(camera, T_true, 40, 0.3, seed);
    for (const LineBalance balance : {LineBalance::kPaper, LineBalance::kOne}) {
      Eigen::Isometry3d T = perturbed(T_true, seed);
      std::vector<bool> inlier, line_inlier;
      const double w = lineBalanceFactor(balance, static_cast<int>(points.size()));
      const int n = optimizer.optimize(points, scene.lines, w, T, inlier, line_inlier);
      EXPECT_GE(n, 7) << "seed " << seed;
      EXPECT_LT(translationError(T, T_true), 0.01) << "seed " << seed;
      EXPECT_LT(rotationErrorDeg(T, T_true), 0.2) << "seed " << seed;
      int outliers = 0, flagged = 0;
      for (size_t k = 0; k < line_inlier.size(); ++k) {
        outliers += scene.is_outlier[k];
        flagged += scene.is_outlier[k] && !line_inlier[k];
      }
      EXPECT_GE(flagged, 0.9 * outliers) << "seed " << seed;
    }
  }
}

TEST(PoseOptimizerLines, NoLinesIsThePointOnlyOptimiser) {
  const PinholeCamera camera = makeCamera();
  const PoseOptimizer optimizer(camera, PoseOptimizerParams());
  const Eigen::Isometry3d T_true = truePose();
  const auto points = makePoints(camera, T_true, 50, 7);
  Eigen::Isometry3d a = perturbed(T_true, 7), b = a;
  std::vector<bool> inlier_a, inlier_b, line_inlier;
  EXPECT_EQ(optimizer.optimize(points, a, inlier_a),
            optimizer.optimize(points, {}, 5.0, b, inlier_b, line_inlier));
  EXPECT_TRUE(a.matrix() == b.matrix());
  EXPECT_EQ(inlier_a, inlier_b);
}

struct RunResult {
  Trajectory trajectory;
  size_t lost = 0, map_lines = 0, map_points = 0;
  double lines_ms = 0.0;
  long line_inliers = 0;
};

RunResult runSequence(const TumSequence& sequence, const SystemConfig& config) {
  System system(config);
  RunResult run;
  for (size_t i = 0; i < sequence.size(); ++i) {
    const FrameResult r = system.process(sequence.load(i, config.camera.depth_factor));
    run.lost += r.tracking.state != TrackingState::kOk;
    run.lines_ms += r.timing.lines_ms;
    run.line_inliers += r.tracking.line_inliers;
  }
  run.trajectory = system.cameraTrajectory();
  run.map_lines = system.map().numMapLines();
  run.map_points = system.map().numMapPoints();
  return run;
}

// lines.enabled false: no line work in tracking, and the line parameters cannot change the result
// (place recognition describes keyframes' lines, but no loop is found in 1.2 s).
TEST(LineTracking, DisabledIsExactlyPointsOnly) {
  const std::string folder = test::sharedPath("data/tum/rgbd_dataset_freiburg1_xyz_37");
  PLY_SLAM_REQUIRE_SHARED(folder);
  const TumSequence sequence(folder);
  SystemConfig config = loadConfig(std::string(PLY_SLAM_SOURCE_DIR) + "/config/tum_fr1.yaml");
  config.lines.enabled = false;
  const RunResult a = runSequence(sequence, config);
  SystemConfig other = config;  // every line setting different
  other.lines.balance =
      config.lines.balance == LineBalance::kOne ? LineBalance::kPaper : LineBalance::kOne;
  other.lines.max_lines = 3;
  other.lines.max_descriptor_distance = 200;
  other.lines.match_distance_px = 100.0;
  const RunResult b = runSequence(sequence, other);
  EXPECT_EQ(a.lost, 0u);
  EXPECT_EQ(a.map_lines, 0u);
  EXPECT_EQ(a.lines_ms, 0.0);
  EXPECT_EQ(a.line_inliers, 0);
  ASSERT_EQ(a.trajectory.size(), b.trajectory.size());
  for (size_t i = 0; i < a.trajectory.size(); ++i)
    EXPECT_TRUE(a.trajectory[i].T_wc.matrix() == b.trajectory[i].T_wc.matrix()) << "frame " << i;
  EXPECT_EQ(a.map_points, b.map_points);
  EXPECT_LE(computeAte(sequence.groundTruth(), a.trajectory).translation.rmse, 0.006);

  config.lines.enabled = true;
  const RunResult c = runSequence(sequence, config);
  EXPECT_EQ(c.lost, 0u);
  EXPECT_GT(c.map_lines, 0u);
  EXPECT_GT(c.lines_ms, 0.0);
  EXPECT_GT(c.line_inliers, 0);
  EXPECT_LE(computeAte(sequence.groundTruth(), c.trajectory).translation.rmse, 0.006);
}

// The tracker matches lines through LineMatcher, observed-length gate included: frame 4 of
// fr1_xyz_37 with each segment cut to half a pixel about its middle (same line, direction and
// descriptor, so every other gate still passes) gets no line match; whole, it gets many.
TEST(LineTracking, SegmentsShorterThanAPixelAreNotMatched) {
  const std::string folder = test::sharedPath("data/tum/rgbd_dataset_freiburg1_xyz_37");
  PLY_SLAM_REQUIRE_SHARED(folder);
  const TumSequence sequence(folder);
  SystemConfig config = loadConfig(std::string(PLY_SLAM_SOURCE_DIR) + "/config/tum_fr1.yaml");
  config.lines.enabled = true;
  const OrbExtractor orb(config.orb);
  const LineExtractor line_extractor(config.lines);
  const LineFitter fitter(config.lines, config.camera);
  const auto frame = [&](size_t i) {
    const RgbdImages images = sequence.load(i, config.camera.depth_factor);
    cv::Mat gray;
    cv::cvtColor(images.rgb, gray, cv::COLOR_BGR2GRAY);
    Frame f(static_cast<long>(i), images.stamp,
            FrameFeatures::extract(gray, images.depth, config.camera, orb));
    f.setLines(FrameLines::extract(gray, images.depth, config.camera, line_extractor, fitter));
    return f;
  };
  const auto lineInliers = [&](bool shorten) {
    Map map;
    LandmarkCreator mapping(config.camera, config.tracking.max_point_depth, config.lines, map);
    Tracker tracker(config.camera, config.tracking, config.orb, config.lines, map, mapping);
    for (size_t i = 0; i < 4; ++i) {
      Frame f = frame(i);
      EXPECT_EQ(tracker.track(f).state, TrackingState::kOk) << "frame " << i;
    }
    Frame f = frame(4);
    if (shorten) {
      for (LineFeature& l : f.lines.lines) {
        const Eigen::Vector2d middle = 0.5 * (l.start + l.end), half = 0.25 * l.direction();
        l.start = middle - half;
        l.end = middle + half;
      }
    }
    const TrackingResult r = tracker.track(f);
    EXPECT_EQ(r.state, TrackingState::kOk);
    return r.line_inliers;
  };
  EXPECT_GE(lineInliers(false), 20);
  EXPECT_EQ(lineInliers(true), 0);
}

}  // namespace
}  // namespace ply_slam
