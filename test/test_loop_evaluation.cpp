// Precision-recall curves and the ground truth of loops (eval module).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <stdexcept>

#include "ply_slam/eval/loop_ground_truth.h"
#include "ply_slam/eval/pr_plot.h"
#include "ply_slam/eval/precision_recall.h"

namespace ply_slam {
namespace {

TEST(PrecisionRecall, HandComputedCurve) {
  // Scores 0.9 (right), 0.8 (wrong), 0.7 (right), 0.7 (wrong); 4 things to find.
  const PrCurve c = precisionRecall({{0.7, true}, {0.9, true}, {0.8, false}, {0.7, false}}, 4);
  ASSERT_EQ(c.points.size(), 3u);  // the two 0.7 fire together
  EXPECT_DOUBLE_EQ(c.points[0].threshold, 0.9);
  EXPECT_DOUBLE_EQ(c.points[0].precision, 1.0);
  EXPECT_DOUBLE_EQ(c.points[0].recall, 0.25);
  EXPECT_DOUBLE_EQ(c.points[1].precision, 0.5);
  EXPECT_DOUBLE_EQ(c.points[1].recall, 0.25);
  EXPECT_EQ(c.points[2].detections, 4);
  EXPECT_EQ(c.points[2].true_positives, 2);
  EXPECT_DOUBLE_EQ(c.points[2].precision, 0.5);
  EXPECT_DOUBLE_EQ(c.points[2].recall, 0.5);
  EXPECT_DOUBLE_EQ(c.average_precision, 0.25 * 1.0 + 0.25 * 0.5);
  EXPECT_DOUBLE_EQ(c.recall_at_full_precision, 0.25);
  EXPECT_DOUBLE_EQ(c.threshold_at_full_precision, 0.9);
}

TEST(PrecisionRecall, PerfectAndEmpty) {
  const PrCurve perfect = precisionRecall({{0.5, true}, {0.4, true}, {0.1, false}}, 2);
  EXPECT_DOUBLE_EQ(perfect.average_precision, 1.0);
  EXPECT_DOUBLE_EQ(perfect.recall_at_full_precision, 1.0);
  EXPECT_DOUBLE_EQ(perfect.threshold_at_full_precision, 0.4);
  const PrCurve empty = precisionRecall({}, 0);
  EXPECT_TRUE(empty.points.empty());
  EXPECT_DOUBLE_EQ(empty.average_precision, 0.0);
  EXPECT_TRUE(std::isinf(empty.threshold_at_full_precision));
  EXPECT_THROW(precisionRecall({{0.5, true}}, 0), std::invalid_argument);
}

TEST(PrPlot, WritesAPngAndNamesAFileItCannotWrite) {
  const std::string path =
      (std::filesystem::temp_directory_path() / "ply_slam_test_pr_plot.png").string();
  writePrPlot(path, {{"a", precisionRecall({{0.5, true}, {0.2, false}}, 2)}}, "test");
  EXPECT_GT(std::filesystem::file_size(path), 1000u);
  std::filesystem::remove(path);
  EXPECT_THROW(writePrPlot("/nonexistent/dir/pr.png", {}, "x"), std::runtime_error);
}

PinholeCamera smallCamera() {
  PinholeCamera c;
  c.fx = c.fy = 100.0;
  c.cx = 80.0;
  c.cy = 60.0;
  c.width = 160;
  c.height = 120;
  return c;
}

// A wall 2 m in front of a camera at x.
GroundTruthView wallView(long id, double stamp, double x, double yaw_deg = 0.0) {
  GroundTruthView v;
  v.id = id;
  v.stamp = stamp;
  v.T_wc.translation() = Eigen::Vector3d(x, 0, 0);
  v.T_wc.linear() = Eigen::AngleAxisd(yaw_deg * M_PI / 180.0, Eigen::Vector3d::UnitY()).matrix();
  v.depth = cv::Mat(120, 160, CV_32F, cv::Scalar(0));
  const PinholeCamera c = smallCamera();
  // Depth of the plane z_world = 2 along each pixel's ray.
  for (int r = 0; r < v.depth.rows; ++r)
    for (int u = 0; u < v.depth.cols; ++u) {
      const Eigen::Vector3d ray_w = v.T_wc.linear() * c.backProject(Eigen::Vector2d(u, r), 1.0);
      v.depth.at<float>(r, u) = static_cast<float>(2.0 / ray_w.z());
    }
  return v;
}

TEST(LoopGroundTruth, OverlapOfShiftedViewsOfAWall) {
  const PinholeCamera c = smallCamera();
  LoopGroundTruthParams p;
  // The same view: everything overlaps. The view is 3.2 m wide on the wall 2 m away: shifted
  // by 0.8 m, three quarters of it; by 1.6 m, half.
  EXPECT_NEAR(viewOverlap(wallView(0, 0, 0), wallView(1, 20, 0), c, p), 1.0, 1e-9);
  EXPECT_NEAR(viewOverlap(wallView(0, 0, 0), wallView(1, 20, 0.8), c, p), 0.75, 0.02);
  EXPECT_NEAR(viewOverlap(wallView(0, 0, 0), wallView(1, 20, 1.6), c, p), 0.5, 0.02);
  // A wall at another depth where b looks: nothing agrees.
  GroundTruthView far = wallView(1, 20, 0);
  far.depth.setTo(3.0f);
  EXPECT_DOUBLE_EQ(viewOverlap(wallView(0, 0, 0), far, c, p), 0.0);
}

// A person 1 m in front of the camera over the left half of the image, in its depth and, when
// `marked`, in its movers mask.
GroundTruthView withPersonOnTheLeft(GroundTruthView view, bool marked) {
  const cv::Rect left(0, 0, view.depth.cols / 2, view.depth.rows);
  view.depth = view.depth.clone();  // the caller's view keeps its image
  view.depth(left).setTo(1.0f);
  if (marked) {
    view.movers = cv::Mat::zeros(view.depth.size(), CV_8UC1);
    view.movers(left).setTo(255);
  }
  return view;
}

TEST(LoopGroundTruth, PeopleAreNoPartOfThePlace) {
  const PinholeCamera c = smallCamera();
  LoopGroundTruthParams p;
  const GroundTruthView wall = wallView(0, 0, 0);
  // Unmarked, the person hides half of the wall in b, and in a stands where b sees the wall.
  EXPECT_NEAR(viewOverlap(wall, withPersonOnTheLeft(wallView(1, 20, 0), false), c, p), 0.5, 0.02);
  EXPECT_NEAR(viewOverlap(withPersonOnTheLeft(wall, false), wallView(1, 20, 0), c, p), 0.5, 0.02);
  // Marked, those pixels take no part either way: what is left of the wall agrees everywhere.
  EXPECT_NEAR(viewOverlap(wall, withPersonOnTheLeft(wallView(1, 20, 0), true), c, p), 1.0, 1e-9);
  EXPECT_NEAR(viewOverlap(withPersonOnTheLeft(wall, true), wallView(1, 20, 0), c, p), 1.0, 1e-9);
  // Points of a out of b's view still count against the overlap: of a's wall, a quarter is out of
  // view, half lands on the person (no part), a quarter is seen.
  EXPECT_NEAR(viewOverlap(wall, withPersonOnTheLeft(wallView(1, 20, 0.8), true), c, p), 0.5, 0.03);
}

TEST(LoopGroundTruth, TimeDistanceAngleAndOverlapAllCount) {
  const PinholeCamera c = smallCamera();
  LoopGroundTruthParams p;
  const GroundTruthView a = wallView(0, 0.0, 0.0);
  EXPECT_EQ(loopTruth(a, wallView(1, 12.0, 0.1), c, p), LoopTruth::kTrue);
  EXPECT_EQ(loopTruth(a, wallView(1, 9.0, 0.1), c, p), LoopTruth::kFalse);  // too soon
  // A step further or turned further, the same wall in view: neither way; beyond, false.
  EXPECT_EQ(loopTruth(a, wallView(1, 12.0, 0.4), c, p), LoopTruth::kDontCare);
  EXPECT_EQ(loopTruth(a, wallView(1, 12.0, 0.0, 25), c, p), LoopTruth::kDontCare);
  EXPECT_EQ(loopTruth(a, wallView(1, 12.0, 0.7), c, p), LoopTruth::kFalse);
  EXPECT_EQ(loopTruth(a, wallView(1, 12.0, 0.0, 45), c, p), LoopTruth::kFalse);
  GroundTruthView hidden = wallView(1, 12.0, 0.1);
  hidden.depth.setTo(1.0f);  // something right in front of the camera
  EXPECT_EQ(loopTruth(a, hidden, c, p), LoopTruth::kFalse);
  GroundTruthView hidden_further = wallView(1, 12.0, 0.4);
  hidden_further.depth.setTo(1.0f);
  EXPECT_EQ(loopTruth(a, hidden_further, c, p), LoopTruth::kFalse);  // in the band, no overlap
  p.min_gap_s = 5.0;
  EXPECT_EQ(loopTruth(a, wallView(1, 9.0, 0.1), c, p), LoopTruth::kTrue);
  // The bounds are the truth's own: with the false ones at the true ones there is no band.
  p.false_distance_m = p.max_distance_m;
  p.false_angle_deg = p.max_angle_deg;
  EXPECT_EQ(loopTruth(a, wallView(1, 12.0, 0.4), c, p), LoopTruth::kFalse);
}

}  // namespace
}  // namespace ply_slam
