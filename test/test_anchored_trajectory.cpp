// AnchoredTrajectory: frames follow their keyframe when the map moves, and survive its erasure.
#include <gtest/gtest.h>

#include "ply_slam/map/anchored_trajectory.h"
#include "pose_test_helpers.h"

namespace ply_slam {
namespace {

using test::makePose;

void expectNear(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  EXPECT_LT((a.translation() - b.translation()).norm(), 1e-12);
  EXPECT_LT((a.linear() - b.linear()).norm(), 1e-12);
}

// Two keyframes, three frames; a loop correction moves every keyframe by the same rigid motion:
// every frame moves by it too, so the trajectory's shape is kept.
TEST(AnchoredTrajectory, FramesMoveWithTheirKeyFrames) {
  const Eigen::Isometry3d kf0 = makePose({0, 1, 0}, 10, {0.1, 0, 0});  // T_wc
  const Eigen::Isometry3d kf1 = makePose({1, 0, 0}, -5, {1.0, 0.2, 0});
  const Eigen::Isometry3d c0 = makePose({0, 0, 1}, 3, {0.2, 0, 0});
  const Eigen::Isometry3d c1 = makePose({0, 1, 1}, 12, {0.9, 0.1, 0.1});
  const Eigen::Isometry3d c2 = makePose({1, 1, 0}, -7, {1.3, 0.3, 0});
  AnchoredTrajectory trajectory;
  trajectory.add(1.0, 0, kf0.inverse(), c0.inverse());
  trajectory.add(2.0, 0, kf0.inverse(), c1.inverse());
  trajectory.add(3.0, 1, kf1.inverse(), c2.inverse());
  ASSERT_EQ(trajectory.size(), 3u);

  const Trajectory unchanged = trajectory.trajectory({{0, kf0.inverse()}, {1, kf1.inverse()}});
  expectNear(unchanged[0].T_wc, c0);
  expectNear(unchanged[2].T_wc, c2);
  EXPECT_EQ(unchanged[1].stamp, 2.0);

  const Eigen::Isometry3d correction = makePose({1, 2, 3}, 25, {-0.4, 0.5, 1.0});
  const Trajectory moved =
      trajectory.trajectory({{0, (correction * kf0).inverse()}, {1, (correction * kf1).inverse()}});
  expectNear(moved[1].T_wc, correction * c1);
  expectNear(moved[2].T_wc, correction * c2);

  // Only keyframe 1 moves: frames hanging from keyframe 0 stay.
  const Trajectory partly =
      trajectory.trajectory({{0, kf0.inverse()}, {1, (correction * kf1).inverse()}});
  expectNear(partly[0].T_wc, c0);
  expectNear(partly[2].T_wc, correction * c2);
}

// A culled keyframe's frames hang from the live keyframe made before it, where they are; from
// then on they follow that one.
TEST(AnchoredTrajectory, ErasedAnchorHandsItsFramesToTheKeyFrameBefore) {
  const Eigen::Isometry3d kf0 = makePose({0, 1, 0}, 10, {0.1, 0, 0});
  const Eigen::Isometry3d kf3 = makePose({1, 0, 0}, -5, {1.0, 0.2, 0});
  const Eigen::Isometry3d kf5 = makePose({0, 0, 1}, 8, {1.5, 0.2, 0});
  const Eigen::Isometry3d c = makePose({0, 1, 1}, 12, {1.1, 0.1, 0.1});
  AnchoredTrajectory trajectory;
  trajectory.add(1.0, 3, kf3.inverse(), c.inverse());
  const AnchoredTrajectory::KeyFramePoses live{{0, kf0.inverse()}, {5, kf5.inverse()}};
  EXPECT_EQ(trajectory.reanchor(3, kf3.inverse(), live), 0);
  expectNear(trajectory.trajectory(live)[0].T_wc, c);
  const Eigen::Isometry3d correction = makePose({1, 2, 3}, 25, {-0.4, 0.5, 1.0});
  expectNear(trajectory.trajectory({{0, (correction * kf0).inverse()}, {5, kf5.inverse()}})[0].T_wc,
             correction * c);
  // Nothing hangs from keyframe 5: nothing to do, its id comes back.
  EXPECT_EQ(trajectory.reanchor(5, kf5.inverse(), live), 5);
}

TEST(AnchoredTrajectory, MissingKeyFramesAreErrors) {
  AnchoredTrajectory trajectory;
  trajectory.add(1.0, 3, Eigen::Isometry3d::Identity(), Eigen::Isometry3d::Identity());
  EXPECT_THROW(trajectory.trajectory({{0, Eigen::Isometry3d::Identity()}}), std::invalid_argument);
  EXPECT_THROW(
      trajectory.reanchor(3, Eigen::Isometry3d::Identity(), {{4, Eigen::Isometry3d::Identity()}}),
      std::invalid_argument);
}

}  // namespace
}  // namespace ply_slam
