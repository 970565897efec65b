// LoopCorrector on a hand-built map whose truth is known: keyframes round a 2 m square with
// odometry that turns 0.5 degrees too far and walks 1 % too far per step, each creating a landmark
// its successor also sees. Closing the loop at the start must take the drift out, keep every
// landmark where its keyframe saw it, and report the current keyframe's move.
#include <gtest/gtest.h>

#include <algorithm>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "ply_slam/map/map.h"
#include "ply_slam/mapping/landmark_fuser.h"
#include "ply_slam/mapping/loop_corrector.h"
#include "ply_slam/system/system_config.h"
#include "pose_test_helpers.h"

namespace ply_slam {
namespace {

const std::vector<double> kScales{1.0, 1.2, 1.44, 1.728};
constexpr int kSteps = 20;  // keyframes 0..19 round the square, 20 back at the start

Eigen::Isometry3d yawed(double deg, const Eigen::Vector3d& t) {
  return test::makePose({0, 1, 0}, deg, t);  // about the camera's vertical axis
}

// True camera poses (T_wc): 5 keyframes per side 0.4 m apart, a quarter turn at each corner;
// the last is the first again, 0.1 m to the side.
std::vector<Eigen::Isometry3d> truePath() {
  std::vector<Eigen::Isometry3d> path;
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  for (int k = 0; k < kSteps; ++k) {
    path.push_back(T);
    T = T * Eigen::Translation3d(0, 0, 0.4);
    if (k % 5 == 4) T = T * yawed(90, Eigen::Vector3d::Zero());
  }
  path.push_back(T * Eigen::Translation3d(0.1, 0, 0));
  return path;
}

// What odometry made of it: each step's rotation 0.5 degrees more and its translation 1 % longer.
std::vector<Eigen::Isometry3d> driftedPath(const std::vector<Eigen::Isometry3d>& truth) {
  std::vector<Eigen::Isometry3d> path{truth.front()};
  for (size_t k = 1; k < truth.size(); ++k) {
    Eigen::Isometry3d step = truth[k - 1].inverse() * truth[k];
    step.translation() *= 1.01;
    path.push_back(path.back() * step * yawed(0.5, Eigen::Vector3d::Zero()));
  }
  return path;
}

double maxPositionError(const Map& map, const std::vector<Eigen::Isometry3d>& truth) {
  double worst = 0.0;
  for (const auto& kf : map.keyFrames())
    worst = std::max(worst, (kf->T_wc().translation() - truth[kf->id].translation()).norm());
  return worst;
}

// The drifted square as a map: each keyframe with a landmark 2 m in front of it that its
// successor also sees.
struct SquareMap {
  Map map;
  std::vector<std::shared_ptr<KeyFrame>> keyframes;
  std::vector<std::shared_ptr<MapPoint>> points;

  explicit SquareMap(const std::vector<Eigen::Isometry3d>& drifted) {
    for (size_t k = 0; k < drifted.size(); ++k) {
      auto kf = std::make_shared<KeyFrame>();
      kf->T_cw = drifted[k].inverse();
      kf->features.scales = &kScales;
      kf->features.keypoints.resize(2);  // 0: its own landmark, 1: its predecessor's
      kf->map_points.resize(2);
      kf->parent = keyframes.empty() ? nullptr : keyframes.back().get();
      map.addKeyFrame(kf);
      // No descriptor, no viewing range: fusion leaves the landmarks alone.
      points.push_back(
          map.createMapPoint(drifted[k] * Eigen::Vector3d(0.2, -0.1, 2.0), cv::Mat(), kf->id));
      map.addObservation(*kf, 0, points.back());
      if (k > 0) map.addObservation(*kf, 1, points[k - 1]);
      keyframes.push_back(kf);
    }
  }
};

TEST(LoopCorrector, ClosingTheSquareTakesOutItsDrift) {
  const std::vector<Eigen::Isometry3d> truth = truePath();
  const std::vector<Eigen::Isometry3d> drifted = driftedPath(truth);
  SquareMap square(drifted);
  Map& map = square.map;
  const auto& keyframes = square.keyframes;
  const auto& points = square.points;
  for (size_t k = 0; k < keyframes.size(); ++k) ASSERT_EQ(keyframes[k]->id, static_cast<long>(k));
  KeyFrame& query = *keyframes.back();
  KeyFrame& candidate = *keyframes.front();
  const Eigen::Isometry3d T_query_candidate = truth.back().inverse() * truth.front();
  std::vector<Eigen::Vector3d> seen;  // each landmark in its creating keyframe's camera frame
  for (size_t k = 0; k < points.size(); ++k)
    seen.push_back(keyframes[k]->T_cw * points[k]->position);
  const Eigen::Isometry3d query_before = query.T_wc();
  const double error_before = maxPositionError(map, truth);

  SystemConfig config;
  config.camera = test::makeCamera();
  const LandmarkFuser fuser(config.camera, config.orb, config.mapping);
  LoopCorrector corrector(LoopCorrectionOptions(), fuser, map);
  const LoopCorrection correction = corrector.correct(query, candidate, T_query_candidate);
  const double error_after = maxPositionError(map, truth);
  const double query_error = (query.T_wc().translation() - truth.back().translation()).norm();
  std::cout << "largest keyframe position error " << error_before << " m before, " << error_after
            << " m after; the returning keyframe's " << query_error << " m\n";

  EXPECT_GT(error_before, 0.2);  // the drift is there to be taken out
  EXPECT_LT(error_after, 0.25 * error_before);
  EXPECT_LT(query_error, 0.005);
  EXPECT_EQ(candidate.T_wc().matrix(), truth.front().matrix());  // the old side is the anchor
  EXPECT_EQ(correction.connected_keyframes, 2);  // the query and the keyframe before it
  EXPECT_EQ(corrector.loops().size(), 1u);
  const Eigen::Isometry3d moved = correction.world_correction * query_before;
  EXPECT_LT((moved.translation() - query.T_wc().translation()).norm(), 1e-9);
  EXPECT_LT((moved.linear() - query.T_wc().linear()).norm(), 1e-9);
  for (size_t k = 0; k < points.size(); ++k)
    EXPECT_LT((keyframes[k]->T_cw * points[k]->position - seen[k]).norm(), 1e-9)
        << "landmark " << k;
}

// The tracker's side of a correction on the mapping thread: it is told of the rigid move, and
// while the pose graph is solved it makes a keyframe 0.4 m on from the returning one, with a
// landmark 2 m in front of it.
class TrackerBesideTheCorrection : public CorrectionPauses {
 public:
  TrackerBesideTheCorrection(Map& map, const KeyFrame& query) : map_(map), query_(query) {}

  void movedRigidly(const Eigen::Isometry3d& world_correction) override {
    steps_.push_back("rigid");
    rigid_ = world_correction;
  }
  void pause() override { steps_.push_back("pause"); }
  void unlocked(const std::function<void()>& work) override {
    steps_.push_back("unlocked");
    made_ = std::make_shared<KeyFrame>();
    made_->T_cw = (query_.T_wc() * Eigen::Translation3d(0, 0, 0.4)).inverse();
    made_->features.scales = &kScales;
    made_->features.keypoints.resize(1);
    made_->map_points.resize(1);
    map_.addKeyFrame(made_);
    point_ = map_.createMapPoint(made_->T_wc() * Eigen::Vector3d(0, 0, 2), cv::Mat(), made_->id);
    map_.addObservation(*made_, 0, point_);
    work();
  }

  std::vector<std::string> steps_;
  Eigen::Isometry3d rigid_ = Eigen::Isometry3d::Identity();
  std::shared_ptr<KeyFrame> made_;
  std::shared_ptr<MapPoint> point_;

 private:
  Map& map_;
  const KeyFrame& query_;
};

TEST(LoopCorrector, TheTrackerTracksBetweenTheSteps) {
  const std::vector<Eigen::Isometry3d> truth = truePath();
  const std::vector<Eigen::Isometry3d> drifted = driftedPath(truth);
  const Eigen::Isometry3d T_query_candidate = truth.back().inverse() * truth.front();
  SystemConfig config;
  config.camera = test::makeCamera();
  const LandmarkFuser fuser(config.camera, config.orb, config.mapping);
  // In one hold, as in line.
  SquareMap alone(drifted);
  LoopCorrector(LoopCorrectionOptions(), fuser, alone.map)
      .correct(*alone.keyframes.back(), *alone.keyframes.front(), T_query_candidate);
  // In steps, the tracker making a keyframe meanwhile.
  SquareMap beside(drifted);
  KeyFrame& query = *beside.keyframes.back();
  const Eigen::Isometry3d query_before = query.T_wc();
  TrackerBesideTheCorrection tracker(beside.map, query);
  const LoopCorrection correction =
      LoopCorrector(LoopCorrectionOptions(), fuser, beside.map)
          .correct(query, *beside.keyframes.front(), T_query_candidate, &tracker);

  // Told of the rigid move first, a pause before fusing each current-side keyframe (the query
  // and the one before it), the pose graph solved without the lock.
  EXPECT_EQ(tracker.steps_, (std::vector<std::string>{"rigid", "pause", "pause", "unlocked"}));
  // The rigid move put the query where the loop says.
  EXPECT_LT(
      ((tracker.rigid_ * query_before).matrix() - correction.shift.query_T_wc.matrix()).norm(),
      1e-9);
  // The keyframes the correction knew end where they end in one hold.
  for (size_t k = 0; k < alone.keyframes.size(); ++k)
    EXPECT_LT((alone.keyframes[k]->T_wc().matrix() - beside.keyframes[k]->T_wc().matrix()).norm(),
              1e-9)
        << "keyframe " << k;
  // The one made meanwhile kept its place beside the query, its landmark in front of it.
  const Eigen::Isometry3d offset = query.T_wc().inverse() * tracker.made_->T_wc();
  EXPECT_LT((offset.translation() - Eigen::Vector3d(0, 0, 0.4)).norm(), 1e-9);
  EXPECT_LT((offset.linear() - Eigen::Matrix3d::Identity()).norm(), 1e-9);
  EXPECT_LT((tracker.made_->T_cw * tracker.point_->position - Eigen::Vector3d(0, 0, 2)).norm(),
            1e-9);
  // The whole correction is the query's move from before the rigid one to its end.
  EXPECT_LT(((correction.world_correction * query_before).matrix() - query.T_wc().matrix()).norm(),
            1e-9);
}

}  // namespace
}  // namespace ply_slam
