// Line features: 2D segments on drawn images with known edges, merging, the 3D fit of
// PAPER.md §3.1 against planes of known pose (with noise, outliers, holes and depth edges),
// the "traditional" endpoint method beside it, matching across a known motion, the config
// section, and the reconstruction rate on the shared TUM fr1_xyz_37.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <iostream>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>
#include <random>
#include <string>
#include <vector>

#include "ply_slam/features/edge_refiner.h"
#include "ply_slam/features/frame_lines.h"
#include "ply_slam/features/line_extractor.h"
#include "ply_slam/features/line_fitter.h"
#include "ply_slam/features/line_matcher.h"
#include "ply_slam/features/line_merger.h"
#include "ply_slam/features/registered_depth.h"
#include "ply_slam/io/tum_sequence.h"
#include "ply_slam/synth/synthetic_sequence.h"
#include "ply_slam/system/system_config.h"
#include "shared_data.h"

namespace ply_slam {
namespace {

constexpr double kDegreesPerRadian = 180.0 / 3.14159265358979323846;

// The synthetic scenes' camera, with the depth range of the TUM configs; depth noise: the
// defaults (5 mm at 1 m).
PinholeCamera syntheticCamera() {
  PinholeCamera c = ::ply_slam::syntheticCamera();
  c.min_depth = 0.3;
  c.max_depth = 6.0;
  return c;
}

// The plane n . X = d in the camera frame (n unit).
struct Plane {
  Eigen::Vector3d n;
  double d;
  double depth(const PinholeCamera& c, const Eigen::Vector2d& uv) const {
    const Eigen::Vector3d ray((uv.x() - c.cx) / c.fx, (uv.y() - c.cy) / c.fy, 1.0);
    return d / n.dot(ray);
  }
  Eigen::Vector3d point(const PinholeCamera& c, const Eigen::Vector2d& uv) const {
    return c.backProject(uv, depth(c, uv));
  }
};

// Tilted towards the camera at the bottom: 2.3 m at the top row, 1.8 m at the bottom one.
Plane tiltedPlane() {
  const Eigen::Vector3d n = Eigen::Vector3d(0.0, 0.3, 1.0).normalized();
  return {n, 2.0 * n.z()};
}

// Depth (CV_32F m) of a plane at every pixel centre, with the depth model's noise when
// noise_seed is set.
cv::Mat planeDepth(const PinholeCamera& c, const Plane& plane, int noise_seed = -1) {
  cv::Mat depth(c.height, c.width, CV_32F);
  std::mt19937 rng(noise_seed >= 0 ? noise_seed : 0);
  std::normal_distribution<double> unit(0.0, 1.0);
  for (int v = 0; v < c.height; ++v) {
    for (int u = 0; u < c.width; ++u) {
      double z = plane.depth(c, Eigen::Vector2d(u, v));
      if (noise_seed >= 0) z += std::sqrt(c.depth_noise.variance(z)) * unit(rng);
      depth.at<float>(v, u) = static_cast<float>(z);
    }
  }
  return depth;
}

// A bright filled rectangle: cv::rectangle fills pixels [x0, x1] x [y0, y1], so its edges lie
// between pixel centres, at x0 - 0.5, x1 + 0.5, y0 - 0.5 and y1 + 0.5.
struct DrawnRectangle {
  int x0 = 150, y0 = 120, x1 = 450, y1 = 340;
  Eigen::Vector2d corner(int k) const {  // clockwise from the top left
    const double l = x0 - 0.5, r = x1 + 0.5, t = y0 - 0.5, b = y1 + 0.5;
    const Eigen::Vector2d corners[4] = {{l, t}, {r, t}, {r, b}, {l, b}};
    return corners[k % 4];
  }
  // Edge k from corner k to corner k+1: with the bright inside on the left walking
  // counter-clockwise, the oriented edge runs from corner k+1 to corner k.
  LineFeature edge(int k) const {
    LineFeature l;
    l.start = l.raw_start = corner(k + 1);
    l.end = l.raw_end = corner(k);
    return l;
  }
};

cv::Mat drawnImage(const DrawnRectangle& r) {
  cv::Mat image(480, 640, CV_8U, cv::Scalar(70));
  cv::rectangle(image, cv::Point(r.x0, r.y0), cv::Point(r.x1, r.y1), cv::Scalar(200), cv::FILLED);
  return image;
}

double distanceToLine(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                      const Eigen::Vector2d& b) {
  const Eigen::Vector2d d = (b - a).normalized();
  const Eigen::Vector2d r = p - a;
  return std::abs(r.x() * d.y() - r.y() * d.x());
}

double angleDeg(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::acos(std::clamp(a.normalized().dot(b.normalized()), -1.0, 1.0)) * kDegreesPerRadian;
}

// The detected line lying on the edge from a to b (both endpoints within tolerance), or -1.
int findLineOnEdge(const std::vector<LineFeature>& lines, const Eigen::Vector2d& a,
                   const Eigen::Vector2d& b, double tolerance_px = 1.0) {
  for (size_t i = 0; i < lines.size(); ++i) {
    if (distanceToLine(lines[i].start, a, b) <= tolerance_px &&
        distanceToLine(lines[i].end, a, b) <= tolerance_px)
      return static_cast<int>(i);
  }
  return -1;
}

#define REQUIRE_LSD()                                           \
  do {                                                          \
    if (!LineExtractor::lsdAvailable())                         \
      GTEST_SKIP() << "OpenCV " CV_VERSION                      \
                      " has no LSD; EDLines finds no lines on " \
                      "sparse drawn images";                    \
  } while (0)

// ---------------------------------------------------------------------------------------------
// 2D segments

TEST(LineExtraction, FindsEachDrawnEdgeOnceWithinAPixel) {
  REQUIRE_LSD();
  const DrawnRectangle rect;
  const cv::Mat image = drawnImage(rect);
  const LineExtractor extractor(LineOptions{});
  EXPECT_EQ(extractor.detectorName(), "lsd");
  const std::vector<LineFeature> lines = extractor.detect(image, syntheticCamera());
  ASSERT_EQ(lines.size(), 4u);
  for (int k = 0; k < 4; ++k) {
    const LineFeature truth = rect.edge(k);
    const int i = findLineOnEdge(lines, truth.start, truth.end);
    ASSERT_GE(i, 0) << "edge " << k;
    const LineFeature& l = lines[i];
    // Endpoints near the corners (LSD stops a little short of them), oriented like the
    // truth: the bright inside on the left.
    EXPECT_LT((l.start - truth.start).norm(), 4.0) << "edge " << k;
    EXPECT_LT((l.end - truth.end).norm(), 4.0) << "edge " << k;
    const Eigen::Vector2d left(l.direction().y(), -l.direction().x());
    const Eigen::Vector2d mid = 0.5 * (l.start + l.end);
    const Eigen::Vector2d inside = mid + 4.0 * left, outside = mid - 4.0 * left;
    EXPECT_GT(image.at<uchar>(cvRound(inside.y()), cvRound(inside.x())),
              image.at<uchar>(cvRound(outside.y()), cvRound(outside.x())));
  }
  const cv::Mat descriptors = extractor.describe(image, lines);
  EXPECT_EQ(descriptors.rows, 4);
  EXPECT_EQ(descriptors.cols, 32);
  EXPECT_EQ(descriptors.type(), CV_8U);
}

TEST(LineExtraction, MergingJoinsAnEdgeBrokenInTwo) {
  REQUIRE_LSD();
  const DrawnRectangle rect;
  cv::Mat image = drawnImage(rect);
  // A dark bar across the top edge cuts it into [149.5, 295.5] and [303.5, 450.5].
  cv::rectangle(image, cv::Point(296, 100), cv::Point(303, 140), cv::Scalar(70), cv::FILLED);
  const LineFeature top = rect.edge(0);

  LineOptions unmerged;
  unmerged.merge_gap_px = 0.0;
  std::vector<LineFeature> pieces = LineExtractor(unmerged).detect(image, syntheticCamera());
  int on_top = 0;
  for (const LineFeature& l : pieces)
    on_top += distanceToLine(l.start, top.start, top.end) < 1.0 &&
              distanceToLine(l.end, top.start, top.end) < 1.0;
  EXPECT_EQ(on_top, 2) << "without merging, LSD sees two pieces";

  const std::vector<LineFeature> merged =
      LineExtractor(LineOptions{}).detect(image, syntheticCamera());
  const int i = findLineOnEdge(merged, top.start, top.end);
  ASSERT_GE(i, 0);
  EXPECT_GT(merged[i].length(), 290.0);
  EXPECT_LT((merged[i].start - top.start).norm(), 4.0);
  EXPECT_LT((merged[i].end - top.end).norm(), 4.0);
  on_top = 0;
  for (const LineFeature& l : merged)
    on_top += distanceToLine(l.start, top.start, top.end) < 1.0 &&
              distanceToLine(l.end, top.start, top.end) < 1.0;
  EXPECT_EQ(on_top, 1);
}

LineFeature segment(double x0, double y0, double x1, double y1) {
  LineFeature l;
  l.start = l.raw_start = Eigen::Vector2d(x0, y0);
  l.end = l.raw_end = Eigen::Vector2d(x1, y1);
  return l;
}

// A straight edge through `a` with direction `d` (unit), brighter on the left of d (image axes),
// rendered by 8 x 8 supersampling and the optics' blur of the synthetic camera (0.6 px).
cv::Mat edgeImage(const Eigen::Vector2d& a, const Eigen::Vector2d& d, double bar_px = 0.0) {
  const Eigen::Vector2d left(d.y(), -d.x());
  cv::Mat image(240, 320, CV_32F);
  for (int v = 0; v < image.rows; ++v)
    for (int u = 0; u < image.cols; ++u) {
      double sum = 0.0;
      for (int i = 0; i < 8; ++i)
        for (int j = 0; j < 8; ++j) {
          const Eigen::Vector2d p(u - 0.5 + (j + 0.5) / 8.0, v - 0.5 + (i + 0.5) / 8.0);
          const double side = left.dot(p - a);  // > 0: the bright side
          // bar_px > 0: a dark bar that wide beyond the edge on the dark side, then bright again
          const bool bright = side > 0.0 || (bar_px > 0.0 && side < -bar_px);
          sum += bright ? 190.0 : 60.0;
        }
      image.at<float>(v, u) = static_cast<float>(sum / 64.0);
    }
  cv::GaussianBlur(image, image, cv::Size(0, 0), 0.6);
  cv::Mat out;
  image.convertTo(out, CV_8U);
  return out;
}

TEST(EdgeRefiner, MovesAnOffsetTurnedSegmentOntoTheEdge) {
  const Eigen::Vector2d a(40.0, 100.3), d = Eigen::Vector2d(1.0, 0.18).normalized();
  const Eigen::Vector2d left(d.y(), -d.x());
  for (const double bar : {0.0, 3.0}) {  // a lone edge; the near side of a 3 px dark bar
    const cv::Mat image = edgeImage(a, d, bar);
    // One end 1 px off towards the dark side (the bar's other edge), turned by 0.5 degrees.
    const Eigen::Rotation2Dd turn(-0.5 / kDegreesPerRadian);  // the far end 0.75 px bright side
    Eigen::Vector2d start = a + 20.0 * d - 1.0 * left, end = start + 200.0 * (turn * d);
    ASSERT_TRUE(EdgeRefiner::refine(image, start, end)) << "bar " << bar;
    EXPECT_LT(distanceToLine(start, a, a + d), 0.08) << "bar " << bar;
    EXPECT_LT(distanceToLine(end, a, a + d), 0.08) << "bar " << bar;
    EXPECT_LT(std::abs((end - start).norm() - 200.0), 2.0) << "the extent stays";
  }
}

TEST(EdgeRefiner, LeavesASegmentWithoutAnEdgeOrOfTheOtherPolarity) {
  const Eigen::Vector2d a(40.0, 100.3), d = Eigen::Vector2d(1.0, 0.18).normalized();
  const cv::Mat flat(240, 320, CV_8U, cv::Scalar(128));
  Eigen::Vector2d start = a, end = a + 200.0 * d;
  EXPECT_FALSE(EdgeRefiner::refine(flat, start, end));
  EXPECT_EQ(start, a);
  // The same edge walked the other way has the bright side on its right: not its edge.
  const cv::Mat image = edgeImage(a, d);
  start = a + 200.0 * d, end = a;
  EXPECT_FALSE(EdgeRefiner::refine(image, start, end));
  EXPECT_EQ(end, a);
}

TEST(LineExtraction, RefinedEdgesLieOnTheDrawnEdges) {
  REQUIRE_LSD();
  const DrawnRectangle rect;
  const cv::Mat image = drawnImage(rect);
  // Mean distance of the detected ends to their true edge, with and without the refinement.
  auto offset = [&](bool refine) {
    LineOptions params;
    params.refine_edges = refine;
    const std::vector<LineFeature> lines = LineExtractor(params).detect(image, syntheticCamera());
    double sum = 0.0;
    for (int k = 0; k < 4; ++k) {
      const LineFeature truth = rect.edge(k);
      const int i = findLineOnEdge(lines, truth.start, truth.end);
      if (i < 0) return 1e9;
      sum += distanceToLine(lines[i].start, truth.start, truth.end) +
             distanceToLine(lines[i].end, truth.start, truth.end);
    }
    return sum / 8.0;
  };
  const double refined = offset(true), detected = offset(false);
  std::cout << "[ measured ] drawn edges, mean end offset: LSD " << detected << " px, refined "
            << refined << " px\n";
  EXPECT_LT(refined, 0.05);
  EXPECT_LT(refined, 0.5 * detected);
}

TEST(LineMerger, JoinsCollinearPiecesAndLeavesOtherLinesAlone) {
  const LineMerger merger(LineOptions{});  // 3 deg, 2 px, gap 20 px
  // Collinear pieces, 1 deg apart, 0.2 px offset, 10 px gap: one segment over both.
  const double slope = std::tan(1.0 / kDegreesPerRadian);
  std::vector<LineFeature> joined =
      merger.merge({segment(100, 200, 300, 200), segment(310, 200.2, 400, 200.2 + 90 * slope)});
  ASSERT_EQ(joined.size(), 1u);
  EXPECT_NEAR(joined[0].start.x(), 100.0, 0.5);
  EXPECT_NEAR(joined[0].end.x(), 400.0, 0.5);
  EXPECT_NEAR(joined[0].start.y(), 200.0, 1.0);
  // Overlapping duplicates of one edge merge too.
  EXPECT_EQ(merger.merge({segment(100, 50, 300, 50), segment(250, 50.5, 350, 50.5)}).size(), 1u);

  // Crossing lines, parallel lines 5 px apart, the two sides of a thin bar (opposite
  // polarity), and collinear pieces 40 px apart all stay separate.
  EXPECT_EQ(merger.merge({segment(100, 100, 300, 300), segment(100, 300, 300, 100)}).size(), 2u);
  EXPECT_EQ(merger.merge({segment(100, 100, 400, 100), segment(100, 105, 400, 105)}).size(), 2u);
  EXPECT_EQ(merger.merge({segment(100, 100, 400, 100), segment(400, 101, 100, 101)}).size(), 2u);
  EXPECT_EQ(merger.merge({segment(100, 100, 200, 100), segment(240, 100, 340, 100)}).size(), 2u);
  // Slightly more than merge_angle_deg apart: separate.
  const double steep = std::tan(4.0 / kDegreesPerRadian);
  EXPECT_EQ(
      merger.merge({segment(100, 100, 300, 100), segment(305, 100, 405, 100 + 100 * steep)}).size(),
      2u);
}

// ---------------------------------------------------------------------------------------------
// 3D segments

TEST(LineFitter, CovarianceIsJLambdaJtOfTheSample) {
  const PinholeCamera camera = syntheticCamera();
  LineOptions params;
  params.sigma_px = 1.0;
  const LineFitter fitter(params, camera);
  const double u = 412.0, v = 97.0, z = 2.4;
  // By hand: X = (u - cx) z / fx, Y = (v - cy) z / fy; J = [[z/fx, 0, X/z], [0, z/fy, Y/z],
  // [0, 0, 1]], Lambda = diag(1, 1, sZ2): Sigma = J Lambda J^T element by element.
  const double X = (u - camera.cx) * z / camera.fx, Y = (v - camera.cy) * z / camera.fy;
  const double sZ2 =
      camera.depth_noise.alpha * z * z + camera.depth_noise.beta * z + camera.depth_noise.gamma;
  const double a = z / camera.fx, b = z / camera.fy, p = X / z, q = Y / z;
  Eigen::Matrix3d expected;
  expected << a * a + p * p * sZ2, p * q * sZ2, p * sZ2,  //
      p * q * sZ2, b * b + q * q * sZ2, q * sZ2,          //
      p * sZ2, q * sZ2, sZ2;
  const Eigen::Matrix3d sigma = fitter.sampleCovariance(Eigen::Vector2d(u, v), z);
  EXPECT_LT((sigma - expected).cwiseAbs().maxCoeff(), 1e-15) << sigma << "\nvs\n" << expected;
  // sigma_px scales the image terms only.
  params.sigma_px = 2.0;
  const Eigen::Matrix3d sigma2 = LineFitter(params, camera).sampleCovariance({u, v}, z);
  EXPECT_NEAR(sigma2(0, 0) - sigma(0, 0), 3.0 * a * a, 1e-15);
  EXPECT_NEAR(sigma2(2, 2), sZ2, 1e-15);
}

TEST(LineFitter, MahalanobisDistanceToALine) {
  // Isotropic covariance: the squared Euclidean distance over the variance.
  const Eigen::Matrix3d cov = 0.01 * Eigen::Matrix3d::Identity();
  EXPECT_NEAR(LineFitter::mahalanobisToLine({1.0, 0.3, 5.0}, cov.inverse(), {0, 0, 5}, {2, 0, 0}),
              9.0, 1e-12);
  // Anisotropic: an offset along the noisy axis costs less.
  Eigen::Matrix3d aniso = Eigen::Vector3d(1e-4, 1e-4, 1e-2).asDiagonal();
  const Eigen::Matrix3d info = aniso.inverse();
  EXPECT_NEAR(LineFitter::mahalanobisToLine({0, 0, 0.1}, info, {0, 0, 0}, {1, 0, 0}), 1.0, 1e-12);
  EXPECT_NEAR(LineFitter::mahalanobisToLine({0, 0.1, 0}, info, {0, 0, 0}, {1, 0, 0}), 100.0, 1e-9);
}

TEST(LineFitter, SampledFitRecoversTheDrawnEdgesOnATiltedPlane) {
  REQUIRE_LSD();
  const PinholeCamera camera = syntheticCamera();
  const Plane plane = tiltedPlane();
  const DrawnRectangle rect;
  const LineOptions params;
  const LineExtractor extractor(params);
  const LineFitter fitter(params, camera);
  const FrameLines f = FrameLines::extract(drawnImage(rect), planeDepth(camera, plane, 7), camera,
                                           extractor, fitter, LineFitMethod::kSampled);
  ASSERT_EQ(f.size(), 4u);
  EXPECT_DOUBLE_EQ(f.reconstructionRate(), 1.0);
  for (int k = 0; k < 4; ++k) {
    const LineFeature truth = rect.edge(k);
    const int i = findLineOnEdge(f.lines, truth.start, truth.end);
    ASSERT_GE(i, 0) << "edge " << k;
    const Line3D& l = f.lines3d[i];
    ASSERT_TRUE(l.valid) << "edge " << k;
    const Eigen::Vector3d A = plane.point(camera, truth.start), B = plane.point(camera, truth.end);
    EXPECT_LT((l.start - A).norm(), 0.02) << "edge " << k << ": " << l.start.transpose();
    EXPECT_LT((l.end - B).norm(), 0.02) << "edge " << k << ": " << l.end.transpose();
    EXPECT_LT(angleDeg(l.direction(), B - A), 1.0) << "edge " << k;
    EXPECT_EQ(l.samples, std::min(f.average_length, static_cast<int>(f.lines[i].length())) + 1);
    EXPECT_GT(l.inliers, 0.9 * l.samples);
  }
}

// Samples of the segment A-B as fitSampled makes them: pixel and depth noise (1 px, the
// depth model's sigma), and outliers: the given fraction of samples with their depth from a
// surface 15-50 % farther or nearer.
struct Samples {
  std::vector<Eigen::Vector3d> points;
  std::vector<Eigen::Matrix3d> covariances;
  int outliers = 0;
};

Samples noisySamples(const LineFitter& fitter, const PinholeCamera& camera,
                     const Eigen::Vector3d& A, const Eigen::Vector3d& B, int n,
                     double outlier_fraction, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> unit(0.0, 1.0);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  std::vector<int> order(n + 1);
  for (int j = 0; j <= n; ++j) order[j] = j;
  std::shuffle(order.begin(), order.end(), rng);
  std::vector<bool> outlier(n + 1, false);
  const int num_outliers = static_cast<int>(std::round(outlier_fraction * (n + 1)));
  // Not the two ends: the fit ends at the extreme inliers, which must be the true ends.
  order.erase(std::remove_if(order.begin(), order.end(), [n](int j) { return j == 0 || j == n; }),
              order.end());
  for (int k = 0; k < num_outliers; ++k) outlier[order[k]] = true;
  Samples s;
  s.outliers = num_outliers;
  for (int j = 0; j <= n; ++j) {
    const Eigen::Vector3d P = A + (B - A) * (static_cast<double>(j) / n);
    Eigen::Vector2d uv = camera.project(P);
    double z = P.z();
    uv += Eigen::Vector2d(unit(rng), unit(rng));
    z += std::sqrt(camera.depth_noise.variance(z)) * unit(rng);
    if (outlier[j])
      z *= uniform(rng) < 0.5 ? 1.15 + 0.35 * uniform(rng) : 0.85 - 0.35 * uniform(rng);
    s.points.push_back(camera.backProject(uv, z));
    s.covariances.push_back(fitter.sampleCovariance(uv, z));
  }
  return s;
}

TEST(LineFitter, RansacRecoversASegmentFromNoisySamplesWith30PercentOutliers) {
  const PinholeCamera camera = syntheticCamera();
  const LineFitter fitter(LineOptions{}, camera);
  // 1.2 m long, receding from 1.9 to 2.6 m: the depth noise (1 - 1.4 cm) moves the ends along
  // the line, so "within 2 cm" holds for most ends, as the issue asks (>= 90 %), not all.
  const Eigen::Vector3d A(-0.45, 0.12, 1.9), B(0.5, -0.08, 2.6);
  int ends = 0, ends_within_2cm = 0;
  for (unsigned seed = 1; seed <= 30; ++seed) {
    const Samples s = noisySamples(fitter, camera, A, B, 60, 0.3, seed);
    const Line3D l = fitter.fitPoints(s.points, s.covariances, 61);
    ASSERT_TRUE(l.valid) << "seed " << seed;
    for (const double error : {(l.start - A).norm(), (l.end - B).norm()}) {
      EXPECT_LT(error, 0.04) << "seed " << seed;
      ++ends;
      ends_within_2cm += error < 0.02;
    }
    EXPECT_LT(angleDeg(l.direction(), B - A), 1.0) << "seed " << seed;
    // The outliers (15-50 % off in depth) are no inliers; nearly all clean samples are.
    EXPECT_LE(l.inliers, 61 - s.outliers) << "seed " << seed;
    EXPECT_GE(l.inliers, 0.85 * (61 - s.outliers)) << "seed " << seed;
  }
  EXPECT_GE(ends_within_2cm, 0.9 * ends);

  // The paper's fit alone (no refit) keeps fewer of the clean samples.
  LineOptions paper_only;
  paper_only.refit_rounds = 0;
  const LineFitter paper(paper_only, camera);
  int refit_inliers = 0, paper_inliers = 0;
  for (unsigned seed = 1; seed <= 30; ++seed) {
    const Samples s = noisySamples(fitter, camera, A, B, 60, 0.3, seed);
    refit_inliers += fitter.fitPoints(s.points, s.covariances, 61).inliers;
    paper_inliers += paper.fitPoints(s.points, s.covariances, 61).inliers;
  }
  EXPECT_GT(refit_inliers, paper_inliers);
}

TEST(LineFitter, RansacRejectsDepthOutliersAlongADrawnEdge) {
  const PinholeCamera camera = syntheticCamera();
  const Plane plane = tiltedPlane();
  const DrawnRectangle rect;
  cv::Mat depth = planeDepth(camera, plane, 11);
  // Every third 10-px block along the top edge (not those at the corners) reads a surface
  // 60 cm nearer.
  for (int u = rect.x0; u <= rect.x1; ++u) {
    if (((u - rect.x0) / 10) % 3 != 1) continue;
    for (int v = rect.y0 - 6; v <= rect.y0 + 6; ++v) depth.at<float>(v, u) -= 0.6f;
  }
  const LineFitter fitter(LineOptions{}, camera);
  const LineFeature top = rect.edge(0);
  const Eigen::Vector3d A = plane.point(camera, top.start), B = plane.point(camera, top.end);
  const Line3D l = fitter.fitSampled(top, depth, 100);
  ASSERT_TRUE(l.valid);
  EXPECT_LT((l.start - A).norm(), 0.02) << l.start.transpose();
  EXPECT_LT((l.end - B).norm(), 0.02) << l.end.transpose();
  EXPECT_LT(angleDeg(l.direction(), B - A), 1.0);
  EXPECT_EQ(l.samples, 101);
  EXPECT_NEAR(l.inliers, 101 * 2 / 3, 6);
}

TEST(LineFitter, AcceptanceRejectsTooShortAndTooPoorlySupportedSegments) {
  const PinholeCamera camera = syntheticCamera();
  LineOptions params;
  params.min_length_m = 0.03;
  params.min_inlier_ratio = 0.25;
  const LineFitter fitter(params, camera);
  // The same 30 px segment on a fronto-parallel plane: 2.9 cm long at 0.5 m, 5.7 cm at 1 m.
  const LineFeature l = segment(300, 240, 330, 240);
  const Line3D near = fitter.fitSampled(l, planeDepth(camera, {{0, 0, 1}, 0.5}), 60);
  EXPECT_NEAR(near.length(), 30 * 0.5 / camera.fx, 1e-3);
  EXPECT_EQ(near.inliers, near.samples);
  EXPECT_FALSE(near.valid) << "shorter than Th2";
  const Line3D far = fitter.fitSampled(l, planeDepth(camera, {{0, 0, 1}, 1.0}), 60);
  EXPECT_TRUE(far.valid);

  // Depth along only a fifth of a long segment: a good line, but below Th1.
  cv::Mat depth(480, 640, CV_32F, cv::Scalar(0.f));
  planeDepth(camera, {{0, 0, 1}, 1.0})(cv::Rect(100, 0, 60, 480))
      .copyTo(depth(cv::Rect(100, 0, 60, 480)));
  const Line3D sparse = fitter.fitSampled(segment(100, 240, 400, 240), depth, 300);
  EXPECT_EQ(sparse.samples, 301);
  EXPECT_LT(sparse.valid_depth, 0.25 * sparse.samples);
  EXPECT_FALSE(sparse.valid) << "inlier ratio below Th1";
  // Too few samples with depth for any line.
  EXPECT_FALSE(
      fitter.fitPoints({Eigen::Vector3d(0, 0, 1)}, {Eigen::Matrix3d::Identity()}, 30).valid);
}

TEST(LineFitter, SampledSucceedsWhereTheEndpointsDepthFails) {
  const PinholeCamera camera = syntheticCamera();
  const Plane plane = tiltedPlane();
  const DrawnRectangle rect;
  cv::Mat depth = planeDepth(camera, plane, 3);
  // No depth around the top-left corner; a near object (1 m) over the bottom-right one.
  cv::circle(depth, cv::Point(rect.x0, rect.y0), 10, cv::Scalar(0.f), cv::FILLED);
  cv::circle(depth, cv::Point(rect.x1, rect.y1), 10, cv::Scalar(1.0f), cv::FILLED);
  const LineFitter fitter(LineOptions{}, camera);
  for (int k : {0, 2}) {  // the top edge (hole at its end), the bottom edge (object at its end)
    const LineFeature edge = rect.edge(k);
    const Eigen::Vector3d A = plane.point(camera, edge.start), B = plane.point(camera, edge.end);
    const Line3D sampled = fitter.fitSampled(edge, depth, 120);
    ASSERT_TRUE(sampled.valid) << "edge " << k;
    EXPECT_LT(angleDeg(sampled.direction(), B - A), 1.0) << "edge " << k;
    // The end without usable depth is where the last inlier is: ~10 px short of the corner.
    EXPECT_LT(std::min((sampled.start - A).norm(), (sampled.end - B).norm()), 0.02);
    EXPECT_LT(std::max((sampled.start - A).norm(), (sampled.end - B).norm()), 0.06);

    const Line3D endpoints = fitter.fitEndpoints(edge, depth);
    if (k == 0) {
      EXPECT_FALSE(endpoints.valid) << "no depth at the endpoint";
      EXPECT_EQ(endpoints.valid_depth, 1);
    } else {
      // Accepted, but its end is on the near object: a metre off.
      ASSERT_TRUE(endpoints.valid);
      EXPECT_GT((endpoints.end - B).norm(), 0.5);
      EXPECT_GT(angleDeg(endpoints.direction(), B - A), 10.0);
    }
  }
}

TEST(LineFitter, EndpointMethodOnCleanDepth) {
  const PinholeCamera camera = syntheticCamera();
  const Plane plane = tiltedPlane();
  const DrawnRectangle rect;
  const LineFitter fitter(LineOptions{}, camera);
  const LineFeature edge = rect.edge(1);
  const Line3D l = fitter.fitEndpoints(edge, planeDepth(camera, plane));
  ASSERT_TRUE(l.valid);
  EXPECT_EQ(l.samples, 2);
  EXPECT_EQ(l.inliers, 2);
  EXPECT_LT((l.start - plane.point(camera, edge.start)).norm(), 0.01);
  EXPECT_LT((l.end - plane.point(camera, edge.end)).norm(), 0.01);
}

TEST(RegisteredDepth, DistortionRoundTripsWithOpenCvUndistortion) {
  PinholeCamera camera = syntheticCamera();
  camera.distortion = (cv::Mat_<double>(1, 5) << 0.2624, -0.9531, -0.0054, 0.0026, 1.1633);
  const RegisteredDepth depth(camera);
  std::vector<cv::Point2f> raw = {{20, 30}, {320, 240}, {600, 450}, {100, 400}}, undistorted;
  cv::undistortPoints(raw, undistorted, camera.K(), camera.distortion, cv::noArray(), camera.K());
  for (size_t i = 0; i < raw.size(); ++i) {
    const Eigen::Vector2d back = depth.distort({undistorted[i].x, undistorted[i].y});
    EXPECT_NEAR(back.x(), raw[i].x, 0.05);
    EXPECT_NEAR(back.y(), raw[i].y, 0.05);
  }
}

// ---------------------------------------------------------------------------------------------
// Matching

// Shapes of different sizes and contrasts on the tilted plane, seen from two poses: frame B
// is frame A warped by the plane's homography, its depth the plane in B's frame.
TEST(LineMatcher, MatchesLinesAcrossAKnownMotion) {
  REQUIRE_LSD();
  const PinholeCamera camera = syntheticCamera();
  const Plane plane_a = tiltedPlane();
  cv::Mat image_a(480, 640, CV_8U, cv::Scalar(90));
  cv::rectangle(image_a, cv::Point(60, 50), cv::Point(250, 190), cv::Scalar(210), cv::FILLED);
  cv::rectangle(image_a, cv::Point(330, 70), cv::Point(420, 300), cv::Scalar(30), cv::FILLED);
  cv::rectangle(image_a, cv::Point(470, 120), cv::Point(590, 200), cv::Scalar(160), cv::FILLED);
  const std::vector<cv::Point> triangle = {{100, 420}, {280, 260}, {300, 430}};
  cv::fillConvexPoly(image_a, triangle, cv::Scalar(240));
  const std::vector<cv::Point> quad = {{380, 360}, {560, 330}, {600, 440}, {420, 460}};
  cv::fillConvexPoly(image_a, quad, cv::Scalar(10));

  Eigen::Isometry3d T_ba = Eigen::Isometry3d::Identity();
  T_ba.linear() =
      Eigen::AngleAxisd(2.0 / kDegreesPerRadian, Eigen::Vector3d(0.2, 1, 0.1).normalized())
          .toRotationMatrix();
  T_ba.translation() = Eigen::Vector3d(0.04, -0.02, 0.03);
  const Eigen::Matrix3d K =
      (Eigen::Matrix3d() << camera.fx, 0, camera.cx, 0, camera.fy, camera.cy, 0, 0, 1).finished();
  const Eigen::Matrix3d H =
      K * (T_ba.linear() + T_ba.translation() * plane_a.n.transpose() / plane_a.d) * K.inverse();
  cv::Mat H_cv(3, 3, CV_64F);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) H_cv.at<double>(r, c) = H(r, c);
  cv::Mat image_b;
  cv::warpPerspective(image_a, image_b, H_cv, image_a.size(), cv::INTER_LINEAR,
                      cv::BORDER_REPLICATE);
  const Eigen::Vector3d n_b = T_ba.linear() * plane_a.n;
  const Plane plane_b{n_b, plane_a.d + n_b.dot(T_ba.translation())};

  const LineOptions params;
  const LineExtractor extractor(params);
  const LineFitter fitter(params, camera);
  const FrameLines a =
      FrameLines::extract(image_a, planeDepth(camera, plane_a, 5), camera, extractor, fitter);
  const FrameLines b =
      FrameLines::extract(image_b, planeDepth(camera, plane_b, 6), camera, extractor, fitter);
  ASSERT_GE(a.numLines3D(), 14u);
  ASSERT_GE(b.size(), 14u);

  // A match is right when A's segment, carried by H, lies on B's line.
  auto correct = [&](const LineMatch& m) {
    const LineFeature& la = a.lines[m.a];
    const Eigen::Vector2d s = (H * la.start.homogeneous()).hnormalized();
    const Eigen::Vector2d e = (H * la.end.homogeneous()).hnormalized();
    return std::abs(b.lines[m.b].distance(s)) < 2.0 && std::abs(b.lines[m.b].distance(e)) < 2.0;
  };
  const LineMatcher matcher(params, camera);
  const std::vector<LineMatch> gated = matcher.matchProjected(a, b, T_ba);
  EXPECT_GE(gated.size(), 0.8 * a.numLines3D());
  for (const LineMatch& m : gated) EXPECT_TRUE(correct(m)) << m.a << " -> " << m.b;

  const std::vector<LineMatch> plain = matcher.matchDescriptors(a, b);
  // Descriptors alone: step edges between flat areas look much alike to LBD, so fewer
  // (measured 11 of 19, 10 right); the pose gate is what makes these unambiguous.
  EXPECT_GE(plain.size(), 0.4 * a.size());
  const long right = std::count_if(plain.begin(), plain.end(), correct);
  EXPECT_GE(right, 0.8 * plain.size());
  EXPECT_GT(gated.size(), static_cast<size_t>(right));

  // A wrong prediction (20 cm off) gates the true counterparts out.
  Eigen::Isometry3d T_wrong = T_ba;
  T_wrong.translation() += Eigen::Vector3d(0.2, 0.2, 0.0);
  const std::vector<LineMatch> wrong = matcher.matchProjected(a, b, T_wrong);
  EXPECT_LT(std::count_if(wrong.begin(), wrong.end(), correct), 0.3 * gated.size());
}

// Whether matchSegments, which the tracker matches its landmarks with, matches a landmark that
// projects at `depth` onto (ps, pe) to the one observed segment (the same descriptor).
bool landmarkMatches(const LineMatcher& matcher, const PinholeCamera& camera,
                     const Eigen::Vector2d& ps, const Eigen::Vector2d& pe,
                     const LineFeature& observed, double depth = 2.0) {
  FrameLines b;
  b.lines = {observed};
  b.descriptors = cv::Mat(1, 32, CV_8U, cv::Scalar(7));
  const SegmentToMatch landmark{camera.backProject(ps, depth), camera.backProject(pe, depth),
                                b.descriptors.ptr()};
  return matcher.matchSegments({landmark}, b, Eigen::Isometry3d::Identity()).size() == 1;
}

// Each gate as withinGates states it and as the tracker applies it.
TEST(LineMatcher, GatesOnAngleDistanceOverlapLengthAndView) {
  const PinholeCamera camera = syntheticCamera();
  const LineMatcher matcher(LineOptions{}, camera);  // 10 deg, 15 px
  const auto gates = [&](const Eigen::Vector2d& ps, const Eigen::Vector2d& pe,
                         const LineFeature& observed) {
    const bool matched = landmarkMatches(matcher, camera, ps, pe, observed);
    EXPECT_EQ(matched, matcher.withinGates(ps, pe, observed));
    return matched;
  };
  const LineFeature observed = segment(100, 100, 300, 100);
  EXPECT_TRUE(gates({120, 105}, {280, 110}, observed));
  EXPECT_FALSE(gates({280, 110}, {120, 105}, observed)) << "opposite polarity";
  EXPECT_FALSE(gates({120, 120}, {280, 120}, observed)) << "20 px away";
  EXPECT_FALSE(gates({120, 100}, {280, 140}, observed)) << "14 deg off";
  EXPECT_FALSE(gates({320, 100}, {400, 100}, observed)) << "beside, not over";
  EXPECT_FALSE(gates({120, 100}, {280, 100}, segment(200, 100, 200.5, 100)))
      << "observed shorter than a pixel";
  EXPECT_FALSE(gates({200, 100}, {200.5, 100}, observed)) << "projected shorter than a pixel";
  // An observed segment left of the image (undistortion moves ends there) and a projection
  // 14 or 12 px from it: wholly beyond 30 px (2 x 15) left of the image is out of view.
  const LineFeature outside = segment(-17, 100, -17, 300);
  EXPECT_FALSE(gates({-31, 100}, {-31, 300}, outside)) << "out of view";
  EXPECT_TRUE(gates({-29, 100}, {-29, 300}, outside)) << "in view";
  EXPECT_FALSE(landmarkMatches(matcher, camera, {120, 105}, {280, 110}, observed, 0.04))
      << "nearer than 5 cm";
}

// ---------------------------------------------------------------------------------------------
// Config and real data

TEST(LineConfig, ShippedFr1SectionAndStrictKeys) {
  const SystemConfig config = loadConfig(std::string(PLY_SLAM_SOURCE_DIR) + "/config/tum_fr1.yaml");
  EXPECT_EQ(config.lines.detector, LineDetectorChoice::kAuto);
  EXPECT_DOUBLE_EQ(config.lines.lsd_scale, 0.35);
  EXPECT_EQ(config.lines.lbd_band_width, 5);
  EXPECT_TRUE(config.lines.refine_edges);
  EXPECT_EQ(config.lines.depth_search_px, 3);
  EXPECT_EQ(config.lines.surface_band_px, 5);
  EXPECT_DOUBLE_EQ(config.lines.min_inlier_ratio, 0.25);
  EXPECT_DOUBLE_EQ(config.lines.chi2_inlier, 5.991);
  EXPECT_DOUBLE_EQ(config.lines.min_length_m, 0.03);
}

// An unknown detector's word is refused when the config is loaded (test_config,
// ModesAreParsedIntoEnums); the extractor runs the one chosen.
TEST(LineExtractor, RunsTheChosenDetector) {
  LineOptions params;
  params.detector = LineDetectorChoice::kEdlines;
  EXPECT_EQ(LineExtractor(params).detectorName(), "edlines");
  params.detector = LineDetectorChoice::kAuto;
  EXPECT_EQ(LineExtractor(params).detectorName(),
            LineExtractor::lsdAvailable() ? "lsd" : "edlines");
  params.detector = LineDetectorChoice::kLsd;
  if (LineExtractor::lsdAvailable())
    EXPECT_EQ(LineExtractor(params).detectorName(), "lsd");
  else
    EXPECT_THROW(LineExtractor{params}, std::runtime_error);
}

TEST(RealData, Fr1XyzReconstructionRateOfBothMethods) {
  const std::string folder = test::sharedPath("data/tum/rgbd_dataset_freiburg1_xyz_37");
  PLY_SLAM_REQUIRE_SHARED(folder);
  const SystemConfig config = loadConfig(std::string(PLY_SLAM_SOURCE_DIR) + "/config/tum_fr1.yaml");
  const TumSequence sequence(folder);
  const LineExtractor extractor(config.lines);
  const LineFitter fitter(config.lines, config.camera);
  const LineMatcher matcher(config.lines, config.camera);
  double sampled = 0.0, endpoints = 0.0, lines = 0.0, matches = 0.0;
  FrameLines previous;
  const size_t n = sequence.size();
  for (size_t i = 0; i < n; ++i) {
    const RgbdImages images = sequence.load(i, config.camera.depth_factor);
    cv::Mat gray;
    cv::cvtColor(images.rgb, gray, cv::COLOR_BGR2GRAY);
    FrameLines f = FrameLines::extract(gray, images.depth, config.camera, extractor, fitter);
    sampled += f.reconstructionRate();
    lines += f.size();
    FrameLines traditional = f;
    traditional.fit(images.depth, fitter, LineFitMethod::kEndpoints);
    endpoints += traditional.reconstructionRate();
    if (i > 0) matches += matcher.matchDescriptors(previous, f).size();
    previous = std::move(f);
  }
  sampled /= n;
  endpoints /= n;
  // Measured with config/tum_fr1.yaml (LSD, OpenCV 4.6): 87 % and 70 %, 150 lines per frame.
  EXPECT_GE(sampled, 0.80);
  EXPECT_GE(sampled, endpoints + 0.08);
  EXPECT_GE(lines / n, 100.0);
  EXPECT_GE(matches / (n - 1), 60.0);
  std::cout << "fr1_xyz_37: rate " << 100 * sampled << " % (traditional " << 100 * endpoints
            << " %), " << lines / n << " lines per frame, " << matches / (n - 1)
            << " LBD matches to the previous frame\n";
}

TEST(RealData, EdlinesFallbackFindsLinesOnARealImage) {
  const std::string folder = test::sharedPath("data/tum/rgbd_dataset_freiburg1_xyz_37");
  PLY_SLAM_REQUIRE_SHARED(folder);
  const SystemConfig config = loadConfig(std::string(PLY_SLAM_SOURCE_DIR) + "/config/tum_fr1.yaml");
  LineOptions params = config.lines;
  params.detector = LineDetectorChoice::kEdlines;
  const LineExtractor extractor(params);
  const RgbdImages images = TumSequence(folder).load(0, config.camera.depth_factor);
  cv::Mat gray;
  cv::cvtColor(images.rgb, gray, cv::COLOR_BGR2GRAY);
  const LineFitter fitter(params, config.camera);
  const FrameLines f = FrameLines::extract(gray, images.depth, config.camera, extractor, fitter);
  EXPECT_GE(f.size(), 50u);
  EXPECT_EQ(f.descriptors.rows, static_cast<int>(f.size()));
  EXPECT_GE(f.reconstructionRate(), 0.6);
}

}  // namespace
}  // namespace ply_slam
