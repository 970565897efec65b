// LocalBundleAdjuster: keyframe poses, points and (issue #4) line landmarks around a new
// keyframe, on a small map with exact observations, so every correction has a known answer.
#include <gtest/gtest.h>

#include <memory>
#include <random>
#include <vector>

#include "ply_slam/common/config.h"
#include "ply_slam/map/map.h"
#include "ply_slam/mapping/local_bundle_adjuster.h"
#include "pose_test_helpers.h"

namespace ply_slam {
namespace {

using namespace ::ply_slam::test;

const std::vector<double> kScales{1.0};

struct TrueSegment {
  Eigen::Vector3d a, b;
};

// Four keyframes 10 cm apart looking along z at 60 points 2-5 m away (pixels and depths
// exact) and six vertical segments 3-4 m away (each keyframe's 2D segment exact).
class SmallMap : public testing::Test {
 protected:
  void SetUp() override {
    config_.camera = makeCamera();
    config_.lines.residual_sigma_px = 1.0;
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> x(-1.5, 1.5), y(-1.0, 1.0), z(2.0, 5.0);
    for (int k = 0; k < 60; ++k) points_.push_back({x(rng), y(rng), z(rng)});
    for (int k = 0; k < 6; ++k) {
      const double px = -0.9 + 0.35 * k, pz = 3.0 + 0.2 * k;
      segments_.push_back({{px, -0.4, pz}, {px + 0.02, 0.4, pz + 0.1}});
    }
    for (int f = 0; f < 4; ++f) {
      auto kf = std::make_shared<KeyFrame>();
      kf->T_cw = makePose({0.2, 1.0, 0.1}, 1.5 * f, {-0.1 * f, 0.02 * f, 0.0});
      map_.addKeyFrame(kf);
      keyframes_.push_back(kf);
    }
    for (const auto& kf : keyframes_) {
      FrameFeatures& features = kf->features;
      features.scales = &kScales;
      for (const Eigen::Vector3d& p : points_) {
        const Eigen::Vector3d c = kf->T_cw * p;
        cv::KeyPoint keypoint;
        const Eigen::Vector2d uv = config_.camera.project(c);
        keypoint.pt = cv::Point2f(static_cast<float>(uv.x()), static_cast<float>(uv.y()));
        features.keypoints.push_back(keypoint);
        features.undistorted.push_back(uv);
        features.rectified.push_back(uv);
        features.depth.push_back(static_cast<float>(c.z()));
      }
      kf->map_points.resize(points_.size());
      for (const TrueSegment& s : segments_) {
        LineFeature l;
        l.start = config_.camera.project(kf->T_cw * s.a);
        l.end = config_.camera.project(kf->T_cw * s.b);
        kf->lines.push_back(l);
      }
      kf->map_lines.resize(segments_.size());
    }
    for (size_t i = 0; i < points_.size(); ++i) {
      auto point = map_.createMapPoint(points_[i], cv::Mat::zeros(1, 32, CV_8U), 0);
      for (const auto& kf : keyframes_) map_.addObservation(*kf, i, point);
    }
  }

  // Map lines moved `offset` m sideways from the true segments (across the line and the first
  // keyframe's view of it: what the 2D observations see; along the view only the baseline
  // would), with the prior of fits of `prior_sigma` m.
  void addLines(double offset, double prior_sigma) {
    for (size_t i = 0; i < segments_.size(); ++i) {
      const Eigen::Vector3d d = segments_[i].b - segments_[i].a;
      const Eigen::Vector3d view = 0.5 * (segments_[i].a + segments_[i].b);  // keyframe 0 at 0
      const Eigen::Vector3d shift = offset * d.cross(view).normalized();
      auto line = map_.createMapLine(segments_[i].a + shift, segments_[i].b + shift,
                                     cv::Mat::zeros(1, 32, CV_8U), 0);
      const double w = 1.0 / (prior_sigma * prior_sigma);
      line->fuse(line->start, line->end, w, w);
      for (const auto& kf : keyframes_) kf->map_lines[i] = line;
      lines_.push_back(line);
    }
  }

  // The larger distance of a map line's ends from its true segment's line (m).
  double lineError(size_t i) const {
    const Eigen::Vector3d d = (segments_[i].b - segments_[i].a).normalized();
    auto off = [&](const Eigen::Vector3d& p) {
      const Eigen::Vector3d r = p - segments_[i].a;
      return (r - d * d.dot(r)).norm();
    };
    return std::max(off(lines_[i]->start), off(lines_[i]->end));
  }

  SystemConfig config_;
  Map map_;
  std::vector<Eigen::Vector3d> points_;
  std::vector<TrueSegment> segments_;
  std::vector<std::shared_ptr<KeyFrame>> keyframes_;
  std::vector<std::shared_ptr<MapLine>> lines_;
};

TEST_F(SmallMap, MovedKeyFrameReturnsToItsPose) {
  const Eigen::Isometry3d truth = keyframes_[3]->T_cw;
  keyframes_[3]->T_cw = makePose({1, 0, 0}, 0.5, {0.01, -0.01, 0.02}) * truth;
  const LocalBundleAdjustmentStats stats =
      LocalBundleAdjuster(config_).adjust(map_, *keyframes_[3]);
  EXPECT_EQ(stats.keyframes, 3);  // keyframe 0 holds the gauge
  EXPECT_EQ(stats.points, 60);
  EXPECT_EQ(stats.outliers_removed, 0);
  EXPECT_LT((keyframes_[3]->T_cw.translation() - truth.translation()).norm(), 1e-4);
  EXPECT_LT(rotationErrorDeg(keyframes_[3]->T_cw, truth), 0.01);
}

TEST_F(SmallMap, LineLandmarksMoveOntoTheirObservedLines) {
  addLines(0.03, 0.05);  // 3 cm off, prior of one fit 5 cm uncertain: 0.9 mm after
  const LocalBundleAdjustmentStats stats =
      LocalBundleAdjuster(config_).adjust(map_, *keyframes_[3]);
  EXPECT_EQ(stats.lines, 6);
  EXPECT_EQ(stats.line_observations, 24);
  for (size_t i = 0; i < lines_.size(); ++i) {
    EXPECT_LT(lineError(i), 0.002) << "line " << i;
    // The ends keep their place along the line (the prior), nothing slides away.
    EXPECT_LT((lines_[i]->start - segments_[i].a).norm(), 0.035) << "line " << i;
  }
  // Exact points and poses stay where they were.
  EXPECT_LT((map_.mapPoints()[0]->position - points_[0]).norm(), 1e-4);
}

TEST_F(SmallMap, AWellFusedLineIsHeldByItsPrior) {
  addLines(0.03, 0.0005);  // the fits say 0.5 mm: the 2D observations move it little (29.7 mm)
  LocalBundleAdjuster(config_).adjust(map_, *keyframes_[3]);
  for (size_t i = 0; i < lines_.size(); ++i) EXPECT_GT(lineError(i), 0.02) << "line " << i;
}

}  // namespace
}  // namespace ply_slam

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
