#include "ply_slam/features/edge_refiner.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "ply_slam/common/angles.h"
#include "ply_slam/features/weighted_line_fit.h"

namespace ply_slam {
namespace {

constexpr double kStep = 0.5;          // px between profile samples
constexpr int kHalf = 6;               // profile samples each side: +-3 px
constexpr double kMinRise = 4.0;       // grey levels per half pixel: weaker is no edge
constexpr double kMaxResidual = 0.75;  // px off the first fit: dropped
constexpr double kMaxShift = 2.0;      // px the refined line may move an end
constexpr double kMaxTurn = 3.0;       // degrees it may turn the segment

bool bilinear(const cv::Mat& gray, const Eigen::Vector2d& p, double& value) {
  const double x = p.x(), y = p.y();
  if (x < 0.0 || y < 0.0 || x >= gray.cols - 1 || y >= gray.rows - 1) return false;
  const int u = static_cast<int>(x), v = static_cast<int>(y);
  const double fx = x - u, fy = y - v;
  const uchar* r0 = gray.ptr<uchar>(v) + u;
  const uchar* r1 = gray.ptr<uchar>(v + 1) + u;
  value = (1 - fy) * ((1 - fx) * r0[0] + fx * r0[1]) + fy * ((1 - fx) * r1[0] + fx * r1[1]);
  return true;
}

}  // namespace

bool EdgeRefiner::refine(const cv::Mat& gray, Eigen::Vector2d& start, Eigen::Vector2d& end) {
  CV_Assert(gray.type() == CV_8UC1);
  const double length = (end - start).norm();
  if (length < 4.0) return false;
  const Eigen::Vector2d d = (end - start) / length;
  const Eigen::Vector2d left(d.y(), -d.x());  // the brighter side
  const int samples = std::clamp(static_cast<int>(length / 2.0), 4, 64);

  std::vector<WeightedPoint2> points;
  points.reserve(samples);
  double profile[2 * kHalf + 1];
  for (int k = 0; k < samples; ++k) {
    const Eigen::Vector2d p = start + (end - start) * ((k + 0.5) / samples);
    bool inside = true;
    for (int i = -kHalf; i <= kHalf && inside; ++i)
      inside = bilinear(gray, p + (i * kStep) * left, profile[i + kHalf]);
    if (!inside) continue;
    // Rise towards the left between neighbouring samples, centred on the half steps between.
    double best = kMinRise;
    int best_i = 0;
    double rise[2 * kHalf];
    for (int i = 0; i < 2 * kHalf; ++i) {
      rise[i] = profile[i + 1] - profile[i];
      if (i > 0 && i < 2 * kHalf - 1 && rise[i] > best) best = rise[i], best_i = i;
    }
    if (best_i == 0 || rise[best_i - 1] > best || rise[best_i + 1] > best) continue;
    const double denom = rise[best_i - 1] - 2.0 * best + rise[best_i + 1];
    const double delta = denom < 0.0 ? 0.5 * (rise[best_i - 1] - rise[best_i + 1]) / denom : 0.0;
    const double offset = (best_i + 0.5 + delta - kHalf) * kStep;
    points.push_back({p + offset * left, best});
  }
  const size_t needed = std::max<size_t>(4, samples / 3);
  Eigen::Vector2d centroid, direction;
  if (points.size() < needed || !fitWeightedLine(points, centroid, direction)) return false;
  const Eigen::Vector2d normal(-direction.y(), direction.x());
  points.erase(std::remove_if(points.begin(), points.end(),
                              [&](const WeightedPoint2& e) {
                                return std::abs(normal.dot(e.p - centroid)) > kMaxResidual;
                              }),
               points.end());
  if (points.size() < needed || !fitWeightedLine(points, centroid, direction)) return false;

  if (direction.dot(d) < 0.0) direction = -direction;
  if (degrees(std::acos(std::min(1.0, direction.dot(d)))) > kMaxTurn) return false;
  const Eigen::Vector2d new_start = centroid + direction * direction.dot(start - centroid);
  const Eigen::Vector2d new_end = centroid + direction * direction.dot(end - centroid);
  if ((new_start - start).norm() > kMaxShift || (new_end - end).norm() > kMaxShift) return false;
  start = new_start;
  end = new_end;
  return true;
}

}  // namespace ply_slam
