// LocalBundleAdjuster: keyframe poses and points around a new keyframe, on a small map with
// exact observations, so the correction has a known answer.
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

// Four keyframes 10 cm apart looking along z at 60 points 2-5 m away, every point seen by
// every keyframe with its exact pixel and depth.
class SmallMap : public testing::Test {
 protected:
  void SetUp() override {
    config_.camera = makeCamera();
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> x(-1.5, 1.5), y(-1.0, 1.0), z(2.0, 5.0);
    for (int k = 0; k < 60; ++k) points_.push_back({x(rng), y(rng), z(rng)});
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
        const Eigen::Vector2d uv = config_.camera.project(c);
        cv::KeyPoint keypoint;
        keypoint.pt = cv::Point2f(static_cast<float>(uv.x()), static_cast<float>(uv.y()));
        features.keypoints.push_back(keypoint);
        features.undistorted.push_back(uv);
        features.rectified.push_back(uv);
        features.depth.push_back(static_cast<float>(c.z()));
      }
      kf->map_points.resize(points_.size());
    }
    for (size_t i = 0; i < points_.size(); ++i) {
      auto point = map_.createMapPoint(points_[i], cv::Mat::zeros(1, 32, CV_8U), 0);
      for (const auto& kf : keyframes_) map_.addObservation(*kf, i, point);
    }
  }

  SystemConfig config_;
  Map map_;
  std::vector<Eigen::Vector3d> points_;
  std::vector<std::shared_ptr<KeyFrame>> keyframes_;
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
  EXPECT_LT((map_.mapPoints()[0]->position - points_[0]).norm(), 1e-4);
}

TEST_F(SmallMap, AnObservationFarOffIsRemoved) {
  // Keypoint 5 of keyframe 2 moved 40 px: an outlier after adjustment, unlinked from its point.
  keyframes_[2]->features.undistorted[5] += Eigen::Vector2d(40.0, 0.0);
  const LocalBundleAdjustmentStats stats =
      LocalBundleAdjuster(config_).adjust(map_, *keyframes_[3]);
  EXPECT_EQ(stats.outliers_removed, 1);
  EXPECT_EQ(keyframes_[2]->map_points[5], nullptr);
  // Huber bounds its pull during the solve that finds it (8.9 mm here).
  EXPECT_LT((map_.mapPoints()[5]->position - points_[5]).norm(), 0.02);
}

}  // namespace
}  // namespace ply_slam
