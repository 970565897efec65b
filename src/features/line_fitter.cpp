#include "ply_slam/features/line_fitter.h"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <random>

namespace ply_slam {

LineFitter::LineFitter(const LineOptions& params, const PinholeCamera& camera)
    : params_(params),
      camera_(camera),
      noise_(camera, params.sigma_px),
      depth_(camera),
      refiner_(params, camera) {}

constexpr double kSidePx = 2.0;  // where the two sides of a line are read

double LineFitter::depthNear(const cv::Mat& depth_m, const Eigen::Vector2d& raw,
                             const Eigen::Vector2d& raw_across) const {
  // Kinect-type sensors leave a band of invalid depth along occluding edges, which are
  // exactly where image lines are: step off the line, nearer offsets first. The sample stays
  // on the line; only its depth comes from beside it.
  // At an occluding edge the line belongs to the nearer surface, while the pixel on the line
  // may show either: where the two sides' depths differ by more than noise, take the nearer.
  const double side_a = depth_.atRaw(depth_m, raw + kSidePx * raw_across),
               side_b = depth_.atRaw(depth_m, raw - kSidePx * raw_across);
  if (side_a > 0.0 && side_b > 0.0) {
    const double nearer = std::min(side_a, side_b);
    if (std::abs(side_a - side_b) > camera_.depth_noise.surfaceGap(nearer)) return nearer;
  }
  double z = depth_.atRaw(depth_m, raw);
  for (int k = 1; z <= 0.0 && k <= params_.depth_search_px; ++k) {
    z = depth_.atRaw(depth_m, raw + k * raw_across);
    if (z <= 0.0) z = depth_.atRaw(depth_m, raw - k * raw_across);
  }
  return z;
}

Eigen::Matrix3d LineFitter::sampleCovariance(const Eigen::Vector2d& uv, double z) const {
  return noise_.covariance(camera_.backProject(uv, z));
}

double LineFitter::mahalanobisToLine(const Eigen::Vector3d& p, const Eigen::Matrix3d& info,
                                     const Eigen::Vector3d& a, const Eigen::Vector3d& d) {
  // The line point nearest to p in the metric of Σ, then the residual's squared norm.
  const Eigen::Vector3d r0 = p - a;
  const Eigen::Vector3d info_d = info * d;
  const double t = info_d.dot(r0) / info_d.dot(d);
  const Eigen::Vector3d r = r0 - t * d;
  return r.dot(info * r);
}

int LineFitter::averageLength(const std::vector<LineFeature>& lines) {
  if (lines.empty()) return 0;
  double sum = 0.0;
  for (const LineFeature& l : lines) sum += l.length();
  return static_cast<int>(std::ceil(sum / lines.size()));
}

bool LineFitter::accept(Line3D& line) const {
  line.valid = line.samples > 0 &&
               static_cast<double>(line.inliers) / line.samples > params_.min_inlier_ratio &&
               line.length() > params_.min_length_m;
  return line.valid;
}

Line3D LineFitter::fitPoints(const std::vector<Eigen::Vector3d>& points,
                             const std::vector<Eigen::Matrix3d>& covariances,
                             int num_samples) const {
  Line3D out;
  out.samples = num_samples;
  out.valid_depth = static_cast<int>(points.size());
  const int n = static_cast<int>(points.size());
  if (n < 2) return out;

  std::vector<Eigen::Matrix3d> info(n);
  for (int k = 0; k < n; ++k) info[k] = covariances[k].inverse();

  // Inliers of the line through a with direction d: squared Mahalanobis distance below chi2.
  auto inliersOf = [&](const Eigen::Vector3d& a, const Eigen::Vector3d& d, std::vector<int>& out) {
    out.clear();
    for (int k = 0; k < n; ++k)
      if (mahalanobisToLine(points[k], info[k], a, d) < params_.chi2_inlier) out.push_back(k);
  };
  std::vector<int> inliers, best;
  auto consensus = [&](int i, int j) {
    const Eigen::Vector3d d = points[j] - points[i];
    if (d.squaredNorm() < 1e-12) return;
    inliersOf(points[i], d, inliers);
    if (inliers.size() > best.size()) best.swap(inliers);
  };

  // Few samples: every pair; otherwise random pairs (a fixed seed: the same frame gives the
  // same lines), stopping once a better set is unlikely (99 % confidence).
  const int pairs = n * (n - 1) / 2;
  if (pairs <= params_.ransac_iterations) {
    for (int i = 0; i < n; ++i)
      for (int j = i + 1; j < n; ++j) consensus(i, j);
  } else {
    std::minstd_rand rng(12345u + static_cast<unsigned>(n));
    std::uniform_int_distribution<int> pick(0, n - 1);
    int needed = params_.ransac_iterations;
    for (int it = 0; it < needed && it < params_.ransac_iterations; ++it) {
      int i = pick(rng), j = pick(rng);
      while (j == i) j = pick(rng);
      const size_t before = best.size();
      consensus(std::min(i, j), std::max(i, j));
      if (best.size() > before) {
        const double w = static_cast<double>(best.size()) / n;
        if (w >= 1.0) break;
        needed = static_cast<int>(std::ceil(std::log(0.01) / std::log(1.0 - w * w)));
      }
    }
  }
  if (best.size() < 2) return out;

  // PCA on the inliers: centroid and principal axis.
  Eigen::Vector3d centroid;
  Eigen::Vector3d v;
  auto pca = [&](const std::vector<int>& set) {
    centroid.setZero();
    for (int k : set) centroid += points[k];
    centroid /= static_cast<double>(set.size());
    Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
    for (int k : set) {
      const Eigen::Vector3d r = points[k] - centroid;
      scatter += r * r.transpose();
    }
    v = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(scatter).eigenvectors().col(2);
  };
  pca(best);
  // Beyond the paper: the inliers again against the refined line, and PCA on them. A line
  // through two noisy samples drifts away from the far ends of the segment, whose samples
  // then miss the consensus; the refined line takes them back (refit_rounds = 0: the paper).
  for (int round = 0; round < params_.refit_rounds; ++round) {
    inliersOf(centroid, v, inliers);
    if (inliers.size() < 2 || inliers == best) break;
    best.swap(inliers);
    pca(best);
  }
  // Samples run from the 2D start to the 2D end: the 3D start is the one seen at the start.
  if (v.dot(points[best.back()] - points[best.front()]) < 0.0) v = -v;

  double t_min = 0.0, t_max = 0.0;
  for (size_t m = 0; m < best.size(); ++m) {
    const double t = (points[best[m]] - centroid).dot(v);
    if (m == 0 || t < t_min) t_min = t;
    if (m == 0 || t > t_max) t_max = t;
  }
  out.start = centroid + t_min * v;
  out.end = centroid + t_max * v;
  out.inliers = static_cast<int>(best.size());
  accept(out);
  return out;
}

Line3D LineFitter::fitSampled(const LineFeature& line, const cv::Mat& depth_m,
                              int average_length) const {
  CV_Assert(depth_m.type() == CV_32F);
  // N = min(L_avg, length): long segments get L_avg samples, short ones one per pixel.
  const int length = static_cast<int>(std::floor(line.length()));
  const int N = std::max(1, average_length > 0 ? std::min(average_length, length) : length);
  std::vector<Eigen::Vector3d> points;
  std::vector<Eigen::Matrix3d> covariances;
  points.reserve(N + 1);
  covariances.reserve(N + 1);
  const Eigen::Vector2d d = line.direction(), across(-d.y(), d.x());
  // One px across in raw pixels at either end, in between interpolated (distortion changes
  // it smoothly; distorting every side read cost more than the reads).
  const Eigen::Vector2d across_start = depth_.rawStep(line.start, across),
                        across_end = depth_.rawStep(line.end, across);
  for (int j = 0; j <= N; ++j) {
    const double s = static_cast<double>(j) / N;
    const Eigen::Vector2d p = line.start * (1.0 - s) + line.end * s;
    const double z =
        depthNear(depth_m, depth_.distort(p), across_start * (1.0 - s) + across_end * s);
    if (z <= 0.0) continue;
    points.push_back(camera_.backProject(p, z));
    covariances.push_back(sampleCovariance(p, z));
  }
  const Line3D fit = fitPoints(points, covariances, N + 1);
  // The refined depths replace the fit's only where they still pass the same acceptance.
  Line3D refined = fit;
  return refiner_.refine(line, depth_m, refined) && accept(refined) ? refined : fit;
}

Line3D LineFitter::fitEndpoints(const LineFeature& line, const cv::Mat& depth_m) const {
  CV_Assert(depth_m.type() == CV_32F);
  Line3D out;
  out.samples = 2;
  // The same depth lookup as the samples of fitSampled, for a like-for-like comparison.
  const Eigen::Vector2d d = line.direction(), across(-d.y(), d.x());
  const double zs =
      depthNear(depth_m, depth_.distort(line.start), depth_.rawStep(line.start, across));
  const double ze = depthNear(depth_m, depth_.distort(line.end), depth_.rawStep(line.end, across));
  out.valid_depth = (zs > 0.0) + (ze > 0.0);
  if (out.valid_depth < 2) return out;
  out.start = camera_.backProject(line.start, zs);
  out.end = camera_.backProject(line.end, ze);
  out.inliers = 2;
  accept(out);
  return out;
}

}  // namespace ply_slam
