#include "ply_slam/features/line_matcher.h"

#include "ply_slam/features/best_two.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <opencv2/core/hal/hal.hpp>

namespace ply_slam {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kMinProjectionDepth = 0.05;  // m; endpoints nearer (or behind) do not project

// Hamming distance of two 32-byte LBD rows (OpenCV's, vectorised at run time).
int hamming(const uchar* a, const uchar* b) { return cv::hal::normHamming(a, b, 32); }

}  // namespace

LineMatcher::LineMatcher(const LineParams& params, const PinholeCamera& camera)
    : params_(params),
      camera_(camera),
      cos_max_angle_(std::cos(params.match_angle_deg * kPi / 180.0)) {}

bool LineMatcher::withinGates(const Eigen::Vector2d& ps, const Eigen::Vector2d& pe,
                              const LineFeature& observed) const {
  const Eigen::Vector2d projected = pe - ps;
  const double length = projected.norm();
  if (length < 1.0 || observed.length() < 1.0) return false;
  const Eigen::Vector2d d = projected / length;
  // Directed: both lines are oriented by polarity, which a rigid motion keeps.
  if (d.dot(observed.direction()) < cos_max_angle_) return false;
  const Eigen::Vector3d l = observed.line();
  if (std::abs(l.dot(ps.homogeneous())) > params_.match_distance_px ||
      std::abs(l.dot(pe.homogeneous())) > params_.match_distance_px)
    return false;
  // The two must overlap along the line: endpoints may move (occlusion, detection), but a
  // segment beside the projected one is another edge on the same line.
  const double t0 = (observed.start - ps).dot(d), t1 = (observed.end - ps).dot(d);
  return std::max(t0, t1) > 0.0 && std::min(t0, t1) < length;
}

std::vector<LineMatch> LineMatcher::matchProjected(const FrameLines& a, const FrameLines& b,
                                                   const Eigen::Isometry3d& T_ba) const {
  CV_Assert(a.descriptors.rows == static_cast<int>(a.size()) &&
            b.descriptors.rows == static_cast<int>(b.size()) && a.lines3d.size() == a.size());
  std::vector<LineMatch> candidates;
  for (size_t i = 0; i < a.size(); ++i) {
    if (!a.hasLine3D(i)) continue;
    const Eigen::Vector3d Ps = T_ba * a.lines3d[i].start, Pe = T_ba * a.lines3d[i].end;
    if (Ps.z() < kMinProjectionDepth || Pe.z() < kMinProjectionDepth) continue;
    const Eigen::Vector2d ps = camera_.project(Ps), pe = camera_.project(Pe);
    BestTwo found;
    for (size_t j = 0; j < b.size(); ++j) {
      if (!withinGates(ps, pe, b.lines[j])) continue;
      found.offer(
          hamming(a.descriptors.ptr(static_cast<int>(i)), b.descriptors.ptr(static_cast<int>(j))),
          static_cast<long>(j));
    }
    if (!found.accept(params_.max_descriptor_distance, params_.match_ratio)) continue;
    candidates.push_back({static_cast<int>(i), static_cast<int>(found.index), found.best});
  }
  // Each line of B once: the closest descriptor keeps it.
  std::sort(candidates.begin(), candidates.end(), [](const LineMatch& x, const LineMatch& y) {
    return x.distance != y.distance ? x.distance < y.distance : x.a < y.a;
  });
  std::vector<bool> taken(b.size(), false);
  std::vector<LineMatch> matches;
  for (const LineMatch& m : candidates) {
    if (taken[m.b]) continue;
    taken[m.b] = true;
    matches.push_back(m);
  }
  std::sort(matches.begin(), matches.end(),
            [](const LineMatch& x, const LineMatch& y) { return x.a < y.a; });
  return matches;
}

std::vector<LineMatch> LineMatcher::matchDescriptors(const FrameLines& a,
                                                     const FrameLines& b) const {
  CV_Assert(a.descriptors.rows == static_cast<int>(a.size()) &&
            b.descriptors.rows == static_cast<int>(b.size()));
  const size_t na = a.size(), nb = b.size();
  std::vector<int> distances(na * nb);
  for (size_t i = 0; i < na; ++i)
    for (size_t j = 0; j < nb; ++j)
      distances[i * nb + j] =
          hamming(a.descriptors.ptr(static_cast<int>(i)), b.descriptors.ptr(static_cast<int>(j)));
  // Nearest A line of every B line, for the mutual check.
  std::vector<int> best_a(nb, -1);
  for (size_t j = 0; j < nb; ++j) {
    int best = INT_MAX;
    for (size_t i = 0; i < na; ++i) {
      if (distances[i * nb + j] < best) {
        best = distances[i * nb + j];
        best_a[j] = static_cast<int>(i);
      }
    }
  }
  std::vector<LineMatch> matches;
  for (size_t i = 0; i < na; ++i) {
    BestTwo found;
    for (size_t j = 0; j < nb; ++j) found.offer(distances[i * nb + j], static_cast<long>(j));
    if (!found.accept(params_.max_descriptor_distance, params_.match_ratio)) continue;
    const int best_j = static_cast<int>(found.index);
    if (best_a[best_j] != static_cast<int>(i)) continue;
    matches.push_back({static_cast<int>(i), best_j, found.best});
  }
  return matches;
}

}  // namespace ply_slam
