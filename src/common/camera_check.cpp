#include "ply_slam/common/camera_check.h"

#include <cmath>
#include <opencv2/calib3d.hpp>
#include <sstream>
#include <vector>

namespace ply_slam {
namespace {

// Bounds far outside any real RGB-D camera, close enough to keep every product finite.
constexpr double kMaxImageSide = 100000.0;  // px
constexpr double kMaxFocal = 100000.0;      // px
constexpr double kMaxDistortion = 1000.0;   // |k1 k2 p1 p2 k3|
constexpr double kMaxDepth = 1000.0;        // m
constexpr double kMaxDepthFactor = 1e6;     // raw units per metre
constexpr double kMaxReadout = 0.1;         // s
// px: how far a border pixel may come back after undistortion and distortion. The shipped
// Kinect calibrations come back within 0.14 px.
constexpr double kMaxRoundTrip = 1.0;

std::string text(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

std::optional<CameraProblem> outside(const std::string& key, double value, double lo, double hi,
                                     const std::string& unit) {
  if (std::isfinite(value) && value >= lo && value <= hi) return std::nullopt;
  return CameraProblem{key, "must be a finite number in [" + text(lo) + ", " + text(hi) + "]" +
                                unit + ", got " + text(value)};
}

std::optional<CameraProblem> firstOf(const std::vector<std::optional<CameraProblem>>& checks) {
  for (const auto& problem : checks)
    if (problem) return problem;
  return std::nullopt;
}

std::optional<CameraProblem> distortionProblem(const cv::Mat& distortion) {
  if (distortion.empty()) return std::nullopt;
  cv::Mat d;
  distortion.convertTo(d, CV_64F);
  for (auto it = d.begin<double>(); it != d.end<double>(); ++it)
    if (auto problem = outside("distortion", *it, -kMaxDistortion, kMaxDistortion, ""))
      return problem;
  return std::nullopt;
}

// The pipeline undistorts pixels with OpenCV's fixed number of fixed-point steps
// (PinholeCamera::undistortPixels, the dense cloud). Where they do not converge at the image's
// border (e.g. p2 = 1.16, which no lens has), keypoints and dense points land kilometres away and
// the octree's searches take minutes (issue #53). Checked at the corners and mid-edges.
std::optional<CameraProblem> inversionProblem(const PinholeCamera& c) {
  if (!c.hasDistortion()) return std::nullopt;
  const int n = static_cast<int>(c.distortion.total());
  if (n != 4 && n != 5 && n != 8 && n != 12 && n != 14)
    return CameraProblem{"distortion",
                         "needs 4, 5, 8, 12 or 14 coefficients, got " + std::to_string(n)};
  std::vector<cv::Point2d> border;
  for (double u : {0.0, (c.width - 1) / 2.0, c.width - 1.0})
    for (double v : {0.0, (c.height - 1) / 2.0, c.height - 1.0}) border.emplace_back(u, v);
  std::vector<cv::Point2d> normalised;
  cv::undistortPoints(border, normalised, c.K(), c.distortion);
  std::vector<cv::Point3d> rays;
  for (const cv::Point2d& p : normalised) rays.emplace_back(p.x, p.y, 1.0);
  std::vector<cv::Point2d> back;
  cv::projectPoints(rays, cv::Vec3d(), cv::Vec3d(), c.K(), c.distortion, back);
  for (size_t i = 0; i < border.size(); ++i) {
    const double error = cv::norm(back[i] - border[i]);
    if (!(error <= kMaxRoundTrip))
      return CameraProblem{"distortion", "cannot be undistorted at the image border: pixel (" +
                                             text(border[i].x) + ", " + text(border[i].y) +
                                             ") comes back " + text(error) + " px away"};
  }
  return std::nullopt;
}

std::optional<CameraProblem> depthNoiseProblem(const PinholeCamera& c) {
  const DepthNoiseModel& n = c.depth_noise;
  if (auto problem = firstOf({outside("depth_noise.alpha", n.alpha, -1.0, 1.0, ""),
                              outside("depth_noise.beta", n.beta, -1.0, 1.0, ""),
                              outside("depth_noise.gamma", n.gamma, -1.0, 1.0, ""),
                              outside("depth_noise.delta", n.delta, 0.0, 1.0, "")}))
    return problem;
  if (n.variance(c.min_depth) <= 0 || n.variance(c.max_depth) <= 0)
    return CameraProblem{"depth_noise.alpha",
                         "with beta and gamma must give a positive variance over [min_depth, "
                         "max_depth]"};
  return std::nullopt;
}

}  // namespace

std::optional<CameraProblem> findCameraProblem(const PinholeCamera& c) {
  if (auto problem = firstOf({outside("width", c.width, 1, kMaxImageSide, " px"),
                              outside("height", c.height, 1, kMaxImageSide, " px"),
                              outside("fx", c.fx, 1, kMaxFocal, " px"),
                              outside("fy", c.fy, 1, kMaxFocal, " px"),
                              // Usually inside the image; a crop may move it out.
                              outside("cx", c.cx, -kMaxImageSide, kMaxImageSide, " px"),
                              outside("cy", c.cy, -kMaxImageSide, kMaxImageSide, " px"),
                              distortionProblem(c.distortion),
                              outside("depth_factor", c.depth_factor, 1e-6, kMaxDepthFactor, ""),
                              outside("min_depth", c.min_depth, 1e-6, kMaxDepth, " m"),
                              outside("max_depth", c.max_depth, 1e-6, kMaxDepth, " m"),
                              outside("rolling_shutter_readout", c.rolling_shutter_readout,
                                      -kMaxReadout, kMaxReadout, " s")}))
    return problem;
  if (c.max_depth <= c.min_depth) return CameraProblem{"max_depth", "must be > min_depth"};
  if (auto problem = inversionProblem(c)) return problem;
  return depthNoiseProblem(c);
}

}  // namespace ply_slam
