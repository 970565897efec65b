#include "ply_slam/features/line_merger.h"

#include <algorithm>
#include <cmath>

#include "ply_slam/common/angles.h"
#include "ply_slam/features/line_distance.h"
#include "ply_slam/features/weighted_line_fit.h"

namespace ply_slam {

namespace {

// One segment covering both: the line fitted to the four endpoints, each weighted by the
// length of its segment (a long piece is better located than a short one), clipped to the
// extreme endpoint projections. Keeps a's orientation; raw endpoints come from the pieces
// whose endpoints are the extremes.
LineFeature join(const LineFeature& a, const LineFeature& b) {
  const Eigen::Vector2d* points[4] = {&a.start, &a.end, &b.start, &b.end};
  const Eigen::Vector2d* raws[4] = {&a.raw_start, &a.raw_end, &b.raw_start, &b.raw_end};
  const double length_a = a.length(), length_b = b.length();
  Eigen::Vector2d centroid, direction;
  fitWeightedLine({{a.start, length_a}, {a.end, length_a}, {b.start, length_b}, {b.end, length_b}},
                  centroid, direction);
  if (direction.dot(a.end - a.start) < 0.0) direction = -direction;

  int first = 0, last = 0;
  double t_min = 0.0, t_max = 0.0;
  for (int k = 0; k < 4; ++k) {
    const double t = (*points[k] - centroid).dot(direction);
    if (k == 0 || t < t_min) t_min = t, first = k;
    if (k == 0 || t > t_max) t_max = t, last = k;
  }
  LineFeature merged;
  merged.start = centroid + t_min * direction;
  merged.end = centroid + t_max * direction;
  merged.raw_start = *raws[first];
  merged.raw_end = *raws[last];
  return merged;
}

}  // namespace

LineMerger::LineMerger(const LineOptions& params)
    : max_angle_rad_(radians(params.merge_angle_deg)),
      max_distance_px_(params.merge_distance_px),
      max_gap_px_(params.merge_gap_px) {}

bool LineMerger::mergeable(const LineFeature& a, const LineFeature& b) const {
  const double length_a = a.length(), length_b = b.length();
  if (length_a <= 0.0 || length_b <= 0.0) return false;
  // Directed: the same polarity only, so the two sides of a thin bar stay apart.
  const Eigen::Vector2d da = (a.end - a.start) / length_a, db = (b.end - b.start) / length_b;
  if (da.dot(db) < std::cos(max_angle_rad_)) return false;
  // The shorter one's endpoints against the longer one's line: the other way round, a small
  // angle over a long lever arm would exceed any sensible distance.
  const LineFeature& longer = length_a >= length_b ? a : b;
  const LineFeature& shorter = length_a >= length_b ? b : a;
  const Eigen::Vector3d l = longer.line();
  if (std::abs(lineDistance(l, shorter.start)) > max_distance_px_ ||
      std::abs(lineDistance(l, shorter.end)) > max_distance_px_)
    return false;
  // Gap along the longer line between the two intervals (negative when they overlap).
  const Eigen::Vector2d d = longer.direction();
  const double t0 = (shorter.start - longer.start).dot(d);
  const double t1 = (shorter.end - longer.start).dot(d);
  const double gap = std::max(std::min(t0, t1) - longer.length(), -std::max(t0, t1));
  return gap <= max_gap_px_;
}

std::vector<LineFeature> LineMerger::merge(std::vector<LineFeature> lines) const {
  std::sort(lines.begin(), lines.end(),
            [](const LineFeature& x, const LineFeature& y) { return x.length() > y.length(); });
  // Unit directions, kept up to date: most pairs fail the angle test, which must be cheap.
  std::vector<Eigen::Vector2d> directions(lines.size());
  for (size_t i = 0; i < lines.size(); ++i) directions[i] = lines[i].direction();
  const double min_cos = std::cos(max_angle_rad_);
  std::vector<bool> absorbed(lines.size(), false);
  std::vector<LineFeature> out;
  for (size_t i = 0; i < lines.size(); ++i) {
    if (absorbed[i]) continue;
    // A grown segment may now reach pieces it missed before: repeat until nothing joins.
    for (bool grew = true; grew;) {
      grew = false;
      for (size_t j = i + 1; j < lines.size(); ++j) {
        if (absorbed[j] || directions[i].dot(directions[j]) < min_cos) continue;
        if (!mergeable(lines[i], lines[j])) continue;
        lines[i] = join(lines[i], lines[j]);
        directions[i] = lines[i].direction();
        absorbed[j] = true;
        grew = true;
      }
    }
    out.push_back(lines[i]);
  }
  return out;
}

}  // namespace ply_slam
