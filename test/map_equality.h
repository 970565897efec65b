// Test helper: a field-by-field comparison of two maps by id.
#pragma once

#include <gtest/gtest.h>

#include <map>
#include <string>

#include "ply_slam/common/stamped_pose.h"
#include "ply_slam/map/map.h"

namespace ply_slam::test {

inline bool sameBytes(const cv::Mat& a, const cv::Mat& b) {
  return a.size() == b.size() && a.type() == b.type() &&
         (a.empty() || cv::countNonZero(a.reshape(1) != b.reshape(1)) == 0);
}

// Same stamps, same poses to the last bit.
inline void expectSameTrajectory(const Trajectory& a, const Trajectory& b) {
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) {
    ASSERT_EQ(a[i].stamp, b[i].stamp);
    ASSERT_TRUE(a[i].T_wc.matrix() == b[i].T_wc.matrix()) << "pose " << i << " at " << a[i].stamp;
  }
}

// Every field of every keyframe, point and line, exactly; links compared by id.
inline void expectSameMap(const Map& a, const Map& b, const std::string& when) {
  SCOPED_TRACE(when);
  const auto kfs_a = a.keyFrames(), kfs_b = b.keyFrames();
  ASSERT_EQ(kfs_a.size(), kfs_b.size());
  auto id = [](const auto& landmark) { return landmark ? landmark->id : -1L; };
  for (size_t k = 0; k < kfs_a.size(); ++k) {
    const KeyFrame &x = *kfs_a[k], &y = *kfs_b[k];
    ASSERT_EQ(x.id, y.id);
    EXPECT_TRUE(x.T_cw.matrix() == y.T_cw.matrix()) << "keyframe " << x.id;
    EXPECT_EQ(x.frame_id, y.frame_id);
    EXPECT_EQ(x.bad, y.bad);
    EXPECT_EQ(id(x.parent), id(y.parent)) << "keyframe " << x.id;
    ASSERT_EQ(x.map_points.size(), y.map_points.size());
    for (size_t i = 0; i < x.map_points.size(); ++i)
      ASSERT_EQ(id(x.map_points[i]), id(y.map_points[i])) << "keyframe " << x.id << " kp " << i;
    ASSERT_EQ(x.map_lines.size(), y.map_lines.size());
    for (size_t i = 0; i < x.map_lines.size(); ++i)
      ASSERT_EQ(id(x.map_lines[i]), id(y.map_lines[i])) << "keyframe " << x.id << " line " << i;
    std::map<long, int> covisible_x, covisible_y;
    for (const auto& [kf, w] : x.covisibility) covisible_x[kf->id] = w;
    for (const auto& [kf, w] : y.covisibility) covisible_y[kf->id] = w;
    EXPECT_EQ(covisible_x, covisible_y) << "keyframe " << x.id;
  }
  const auto points_a = a.mapPoints(), points_b = b.mapPoints();
  ASSERT_EQ(points_a.size(), points_b.size());
  for (size_t k = 0; k < points_a.size(); ++k) {
    const MapPoint &x = *points_a[k], &y = *points_b[k];
    ASSERT_EQ(x.id, y.id);
    EXPECT_EQ(x.position, y.position) << "point " << x.id;
    EXPECT_TRUE(sameBytes(x.descriptor, y.descriptor)) << "point " << x.id;
    EXPECT_EQ(x.normal, y.normal) << "point " << x.id;
    EXPECT_EQ(x.min_distance, y.min_distance);
    EXPECT_EQ(x.max_distance, y.max_distance);
    EXPECT_EQ(x.position_weight, y.position_weight) << "point " << x.id;
    EXPECT_EQ(x.visible, y.visible) << "point " << x.id;
    EXPECT_EQ(x.found, y.found) << "point " << x.id;
    EXPECT_EQ(x.first_keyframe_id, y.first_keyframe_id);
    EXPECT_EQ(x.bad, y.bad);
    EXPECT_EQ(id(x.replaced_by), id(y.replaced_by));
    ASSERT_EQ(x.observers.size(), y.observers.size()) << "point " << x.id;
    for (size_t o = 0; o < x.observers.size(); ++o) {
      EXPECT_EQ(x.observers[o].keyframe->id, y.observers[o].keyframe->id) << "point " << x.id;
      EXPECT_EQ(x.observers[o].index, y.observers[o].index) << "point " << x.id;
    }
  }
  const auto lines_a = a.mapLines(), lines_b = b.mapLines();
  ASSERT_EQ(lines_a.size(), lines_b.size());
  for (size_t k = 0; k < lines_a.size(); ++k) {
    const MapLine &x = *lines_a[k], &y = *lines_b[k];
    ASSERT_EQ(x.id, y.id);
    EXPECT_EQ(x.start, y.start) << "line " << x.id;
    EXPECT_EQ(x.end, y.end) << "line " << x.id;
    EXPECT_EQ(x.start_weight, y.start_weight);
    EXPECT_EQ(x.end_weight, y.end_weight);
    EXPECT_TRUE(sameBytes(x.descriptor, y.descriptor)) << "line " << x.id;
    EXPECT_EQ(x.first_keyframe_id, y.first_keyframe_id);
    EXPECT_EQ(x.observations, y.observations) << "line " << x.id;
    EXPECT_EQ(x.found, y.found) << "line " << x.id;
    EXPECT_EQ(x.bad, y.bad);
  }
}

}  // namespace ply_slam::test
