// Projection matching of landmarks into a frame on a real fr1 image: a landmark behind
// something nearer in the frame's depth image is neither matched nor counted as visible.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>
#include <set>

#include "ply_slam/features/orb_extractor.h"
#include "ply_slam/io/tum_sequence.h"
#include "ply_slam/system/system_config.h"
#include "ply_slam/tracking/projection_matcher.h"
#include "shared_data.h"

namespace ply_slam {
namespace {

TEST(ProjectionMatcher, OccludedLandmarksAreNotVisible) {
  const std::string folder = test::sharedPath("data/tum/rgbd_dataset_freiburg1_xyz_37");
  PLY_SLAM_REQUIRE_SHARED(folder);
  const SystemConfig config = loadConfig(std::string(PLY_SLAM_SOURCE_DIR) + "/config/tum_fr1.yaml");
  const RgbdImages images = TumSequence(folder).load(0, config.camera.depth_factor);
  cv::Mat gray;
  cv::cvtColor(images.rgb, gray, cv::COLOR_BGR2GRAY);
  const OrbExtractor extractor(config.orb);
  const FrameFeatures features =
      FrameFeatures::extract(gray, images.depth, config.camera, extractor);

  // Landmarks where the frame's own features are (the camera at the origin).
  std::vector<std::shared_ptr<MapPoint>> points;
  for (size_t i = 0; i < features.size(); ++i) {
    if (!features.hasDepth(i) || features.depth[i] < 1.0) continue;
    auto p = std::make_shared<MapPoint>();
    p->position = config.camera.backProject(features.undistorted[i], features.depth[i]);
    p->descriptor = features.descriptors.row(static_cast<int>(i)).clone();
    p->normal = p->position.normalized();
    const double scale = features.scale(i);  // seen at its level: the distances that say so
    p->max_distance = p->position.norm() * scale;
    p->min_distance = p->max_distance / extractor.scales().back();
    points.push_back(p);
  }
  ASSERT_GT(points.size(), 200u);

  // Something 0.4 m in front of the camera covers the left half of the depth image.
  Frame frame(1, 0.0, features);
  frame.features.depth_image = images.depth.clone();
  frame.features.depth_image.colRange(0, images.depth.cols / 2).setTo(0.4f);
  const ProjectionMatcher matcher(config.camera, std::log(config.orb.scale_factor),
                                  config.orb.num_levels);
  std::vector<MapPoint*> in_view;
  matcher.match(frame, points, nullptr, {}, in_view);
  const std::set<const MapPoint*> visible(in_view.begin(), in_view.end());

  int left = 0, left_visible = 0, right = 0, right_visible = 0, right_matched = 0;
  for (const auto& p : points) {
    const bool on_left = config.camera.project(p->position).x() < images.depth.cols / 2 - 10;
    const bool on_right = config.camera.project(p->position).x() > images.depth.cols / 2 + 10;
    left += on_left;
    left_visible += on_left && visible.count(p.get());
    right += on_right;
    right_visible += on_right && visible.count(p.get());
  }
  for (size_t i = 0; i < frame.map_points.size(); ++i) {
    if (!frame.map_points[i]) continue;
    EXPECT_GT(frame.features.undistorted[i].x(), images.depth.cols / 2 - 10)
        << "a landmark behind the occluder was matched";
    ++right_matched;
  }
  ASSERT_GT(left, 50);
  ASSERT_GT(right, 50);
  EXPECT_EQ(left_visible, 0);
  // Right of the occluder: in view, and found again (the same image).
  EXPECT_GT(right_visible, 0.9 * right);
  EXPECT_GT(right_matched, 0.8 * right);
}

}  // namespace
}  // namespace ply_slam
