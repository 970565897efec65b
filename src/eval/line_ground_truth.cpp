#include "ply_slam/eval/line_ground_truth.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "ply_slam/common/angles.h"

namespace ply_slam {
namespace {

double distanceToSegment(const Eigen::Vector3d& p, const Segment3& s) {
  const Eigen::Vector3d d = s.b - s.a;
  const double t = std::clamp((p - s.a).dot(d) / d.squaredNorm(), 0.0, 1.0);
  return (s.a + t * d - p).norm();
}

constexpr double kNear = 0.05;  // m: the part of a segment nearer the camera is not imaged

}  // namespace

LineError lineError(const Eigen::Vector3d& start, const Eigen::Vector3d& end,
                    const Segment3& truth) {
  const double distance = std::max(distanceToSegment(start, truth), distanceToSegment(end, truth));
  const double cosine =
      std::min(1.0, std::abs((end - start).normalized().dot((truth.b - truth.a).normalized())));
  return {distance, degrees(std::acos(cosine))};
}

LineError lineError(const Eigen::Vector3d& start, const Eigen::Vector3d& end,
                    const std::vector<Segment3>& truth, const std::vector<size_t>& candidates) {
  LineError best{std::numeric_limits<double>::infinity(), 0.0};
  for (size_t k : candidates) {
    const LineError e = lineError(start, end, truth[k]);
    if (e.endpoint_m < best.endpoint_m) best = e;
  }
  return best;
}

std::vector<size_t> imagedSegments(const LineFeature& line, const std::vector<Segment3>& truth,
                                   const PinholeCamera& camera, const Eigen::Isometry3d& T_cw,
                                   double max_px, double max_deg) {
  std::vector<size_t> found;
  const Eigen::Vector2d d = line.direction();
  for (size_t k = 0; k < truth.size(); ++k) {
    Eigen::Vector3d a = T_cw * truth[k].a, b = T_cw * truth[k].b;
    if (a.z() < kNear && b.z() < kNear) continue;
    // Clip to the part in front of the camera.
    if (a.z() < kNear) a = b + (a - b) * (b.z() - kNear) / (b.z() - a.z());
    if (b.z() < kNear) b = a + (b - a) * (a.z() - kNear) / (a.z() - b.z());
    const Eigen::Vector2d pa = camera.project(a), pb = camera.project(b);
    if ((pb - pa).norm() < 1.0) continue;
    const Eigen::Vector2d e = (pb - pa).normalized();
    if (degrees(std::acos(std::min(1.0, std::abs(d.dot(e))))) > max_deg) continue;
    const Eigen::Vector2d n(-e.y(), e.x());
    const double ds = std::abs(n.dot(line.start - pa)), de = std::abs(n.dot(line.end - pa));
    if (std::max(ds, de) > max_px) continue;
    // Overlap along the line.
    const double t0 = e.dot(line.start - pa), t1 = e.dot(line.end - pa), len = (pb - pa).norm();
    if (std::max(t0, t1) < 0.0 || std::min(t0, t1) > len) continue;
    found.push_back(k);
  }
  return found;
}

}  // namespace ply_slam
