#include "ply_slam/features/line_matcher.h"

#include "ply_slam/common/angles.h"
#include "ply_slam/common/hamming.h"
#include "ply_slam/features/best_two.h"
#include "ply_slam/features/line_distance.h"

#include <algorithm>
#include <climits>
#include <cmath>

namespace ply_slam {

namespace {

constexpr double kMinProjectionDepth = 0.05;  // m; endpoints nearer (or behind) do not project

}  // namespace

// A projected segment: its ends, length and unit direction (px).
struct LineMatcher::Projected {
  Eigen::Vector2d ps, pe, d = Eigen::Vector2d::Zero();
  double length;
  Projected(const Eigen::Vector2d& s, const Eigen::Vector2d& e)
      : ps(s), pe(e), length((e - s).norm()) {
    if (length > 0.0) d = (e - s) / length;
  }
};

// An image segment's line, direction, ends and length, computed once per frame, not per pair.
struct LineMatcher::Observed {
  Eigen::Vector3d l;
  Eigen::Vector2d d, start, end;
  double length;
  explicit Observed(const LineFeature& f)
      : l(f.line()), d(f.direction()), start(f.start), end(f.end), length(f.length()) {}
};

LineMatcher::LineMatcher(const LineOptions& params, const PinholeCamera& camera)
    : params_(params), camera_(camera), cos_max_angle_(std::cos(radians(params.match_angle_deg))) {}

bool LineMatcher::projectedPasses(const Projected& p) const {
  if (p.length < 1.0) return false;
  // Wholly beyond one side of the image by this margin, no segment in the image passes the
  // distance gate (for angles up to 60 deg): skip the pairs.
  const double margin = 2.0 * params_.match_distance_px;
  const double right = camera_.width + margin, bottom = camera_.height + margin;
  return !((p.ps.x() < -margin && p.pe.x() < -margin) ||
           (p.ps.y() < -margin && p.pe.y() < -margin) || (p.ps.x() > right && p.pe.x() > right) ||
           (p.ps.y() > bottom && p.pe.y() > bottom));
}

bool LineMatcher::pairPasses(const Projected& p, const Observed& o) const {
  if (o.length < 1.0) return false;
  // Directed: both lines are oriented by polarity, which a rigid motion keeps.
  if (p.d.dot(o.d) < cos_max_angle_) return false;
  if (std::abs(lineDistance(o.l, p.ps)) > params_.match_distance_px ||
      std::abs(lineDistance(o.l, p.pe)) > params_.match_distance_px)
    return false;
  // The two must overlap along the line: endpoints may move (occlusion, detection), but a
  // segment beside the projected one is another edge on the same line.
  const double t0 = (o.start - p.ps).dot(p.d), t1 = (o.end - p.ps).dot(p.d);
  return std::max(t0, t1) > 0.0 && std::min(t0, t1) < p.length;
}

bool LineMatcher::withinGates(const Eigen::Vector2d& ps, const Eigen::Vector2d& pe,
                              const LineFeature& observed) const {
  const Projected p(ps, pe);
  return projectedPasses(p) && pairPasses(p, Observed(observed));
}

bool LineMatcher::bestLine(const SegmentToMatch& s, const std::vector<Observed>& observed,
                           const cv::Mat& descriptors, const Eigen::Isometry3d& T_bs,
                           LineMatch& m) const {
  const Eigen::Vector3d Ps = T_bs * s.start, Pe = T_bs * s.end;
  if (Ps.z() < kMinProjectionDepth || Pe.z() < kMinProjectionDepth) return false;
  const Projected p(camera_.project(Ps), camera_.project(Pe));
  if (!projectedPasses(p)) return false;
  BestTwo found;
  for (size_t j = 0; j < observed.size(); ++j) {
    if (!pairPasses(p, observed[j])) continue;
    found.offer(
        hammingDistance(s.descriptor, descriptors.ptr(static_cast<int>(j)), descriptors.cols),
        static_cast<long>(j));
  }
  if (!found.accept(params_.max_descriptor_distance, params_.match_ratio)) return false;
  m.b = static_cast<int>(found.index);
  m.distance = found.best;
  return true;
}

std::vector<LineMatch> LineMatcher::matchSegments(const std::vector<SegmentToMatch>& segments,
                                                  const FrameLines& b,
                                                  const Eigen::Isometry3d& T_bs) const {
  CV_Assert(b.descriptors.rows == static_cast<int>(b.size()));
  std::vector<Observed> observed;
  observed.reserve(b.size());
  for (const LineFeature& f : b.lines) observed.emplace_back(f);
  std::vector<LineMatch> candidates;
  for (size_t i = 0; i < segments.size(); ++i) {
    LineMatch m;
    m.a = static_cast<int>(i);
    if (bestLine(segments[i], observed, b.descriptors, T_bs, m)) candidates.push_back(m);
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

std::vector<LineMatch> LineMatcher::matchProjected(const FrameLines& a, const FrameLines& b,
                                                   const Eigen::Isometry3d& T_ba) const {
  CV_Assert(a.descriptors.rows == static_cast<int>(a.size()) && a.lines3d.size() == a.size());
  std::vector<SegmentToMatch> segments;
  std::vector<int> index;  // A's segment of each
  for (size_t i = 0; i < a.size(); ++i) {
    if (!a.hasLine3D(i)) continue;
    segments.push_back(
        {a.lines3d[i].start, a.lines3d[i].end, a.descriptors.ptr(static_cast<int>(i))});
    index.push_back(static_cast<int>(i));
  }
  std::vector<LineMatch> matches = matchSegments(segments, b, T_ba);
  for (LineMatch& m : matches) m.a = index[m.a];
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
          hammingDistance(a.descriptors.ptr(static_cast<int>(i)),
                          b.descriptors.ptr(static_cast<int>(j)), a.descriptors.cols);
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
