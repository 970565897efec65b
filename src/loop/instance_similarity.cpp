#include "ply_slam/loop/instance_similarity.h"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <string>
#include <tuple>

namespace ply_slam {
namespace {

using Boxes = std::vector<cv::Rect2d>;

cv::Point2d centre(const cv::Rect2d& b) { return {b.x + 0.5 * b.width, b.y + 0.5 * b.height}; }

double centreDistance(const cv::Rect2d& a, const cv::Rect2d& b) {
  return cv::norm(centre(a) - centre(b));
}

double iou(const cv::Rect2d& a, const cv::Rect2d& b, double epsilon) {
  const double inter = (a & b).area();
  return inter / (a.area() + b.area() - inter + epsilon);
}

// Sorted diag-normalised distances from box k to the other boxes of its class in its frame.
std::vector<double> neighbourDistances(const Boxes& boxes, size_t k, double diag) {
  std::vector<double> distances;
  for (size_t m = 0; m < boxes.size(); ++m) {
    if (m != k) distances.push_back(centreDistance(boxes[k], boxes[m]) / diag);
  }
  return distances;
}

std::map<std::string, Boxes> staticBoxesByClass(const std::vector<InstanceBox>& boxes,
                                                const std::vector<std::string>& dynamic) {
  std::map<std::string, Boxes> by_class;
  for (const InstanceBox& b : boxes) {
    if (std::find(dynamic.begin(), dynamic.end(), b.class_name) != dynamic.end()) continue;
    by_class[b.class_name].push_back(b.box);
  }
  return by_class;
}

// One class's n1 x n2 matrices: S_pos (for the sure matches) and the adjusted S_inst.
struct ClassScores {
  Eigen::MatrixXd position, instance;
};

double adjustForConsistency(double s_inst, const std::vector<double>& a,
                            const std::vector<double>& b, const LoopOptions& options) {
  const std::optional<double> s_aver = neighbourhoodSimilarity(a, b);
  if (!s_aver) return s_inst;
  if (*s_aver > options.spatial_consistency_threshold) {
    return std::min(1.0, s_inst + options.consistency_boost);
  }
  if (*s_aver < options.spatial_consistency_threshold) {
    return options.consistency_penalty * s_inst;
  }
  return s_inst;
}

ClassScores scoreClass(const Boxes& cur, const Boxes& cand, double diag,
                       const LoopOptions& options) {
  ClassScores s{Eigen::MatrixXd(cur.size(), cand.size()), Eigen::MatrixXd(cur.size(), cand.size())};
  for (size_t i = 0; i < cur.size(); ++i) {
    const std::vector<double> hood_i = neighbourDistances(cur, i, diag);
    for (size_t j = 0; j < cand.size(); ++j) {
      const double s_pos = 1.0 - centreDistance(cur[i], cand[j]) / diag;
      const double s_iou = iou(cur[i], cand[j], options.iou_epsilon);
      const double s_inst = options.position_weight * s_pos + options.iou_weight * s_iou;
      s.position(i, j) = s_pos;
      s.instance(i, j) =
          adjustForConsistency(s_inst, hood_i, neighbourDistances(cand, j, diag), options);
    }
  }
  return s;
}

// Step 1: pairs with S_pos above the sure bound, the most certain first so that an instance
// near two others takes the nearer; each instance matches at most once; each credits 1.
void matchSure(const ClassScores& s, const LoopOptions& options, std::vector<bool>& used_i,
               std::vector<bool>& used_j, InstanceSimilarity& acc, double& total) {
  std::vector<std::tuple<double, int, int>> sure;
  for (int i = 0; i < s.position.rows(); ++i) {
    for (int j = 0; j < s.position.cols(); ++j) {
      if (s.position(i, j) > options.sure_position) sure.emplace_back(s.position(i, j), i, j);
    }
  }
  std::stable_sort(sure.begin(), sure.end(),
                   [](const auto& a, const auto& b) { return std::get<0>(a) > std::get<0>(b); });
  for (const auto& [pos, i, j] : sure) {
    if (used_i[i] || used_j[j]) continue;
    used_i[i] = used_j[j] = true;
    ++acc.matches;
    total += 1.0;
  }
}

// Step 2: repeatedly the best pair of still unmatched instances; it matches when its S_inst
// exceeds Th_dyna, and when the best does not, no other pair can.
void matchGreedy(const ClassScores& s, double threshold, std::vector<bool>& used_i,
                 std::vector<bool>& used_j, InstanceSimilarity& acc, double& total) {
  while (true) {
    int best_i = -1, best_j = -1;
    for (int i = 0; i < s.instance.rows(); ++i) {
      for (int j = 0; j < s.instance.cols(); ++j) {
        if (used_i[i] || used_j[j]) continue;
        if (best_i < 0 || s.instance(i, j) > s.instance(best_i, best_j)) best_i = i, best_j = j;
      }
    }
    if (best_i < 0 || !(s.instance(best_i, best_j) > threshold)) return;
    used_i[best_i] = used_j[best_j] = true;
    ++acc.matches;
    total += s.instance(best_i, best_j);
  }
}

}  // namespace

double dynamicThreshold(size_t n1, size_t n2, const LoopOptions& options) {
  const double n = static_cast<double>(std::min(n1, n2));
  return std::max(options.dyna_floor,
                  std::min(options.dyna_ceiling, options.dyna_ceiling - options.dyna_step * n));
}

std::optional<double> neighbourhoodSimilarity(std::vector<double> a, std::vector<double> b) {
  if (a.empty() || b.empty()) return std::nullopt;
  std::sort(a.begin(), a.end());
  std::sort(b.begin(), b.end());
  const size_t m = std::min(a.size(), b.size());
  double sum = 0.0;
  for (size_t k = 0; k < m; ++k) sum += std::abs(a[k] - b[k]);
  return 1.0 - sum / static_cast<double>(m);
}

InstanceSimilarity instanceSimilarity(const InstanceFrame& current, const InstanceFrame& candidate,
                                      const LoopOptions& options) {
  if (current.image_size != candidate.image_size) {
    throw std::invalid_argument("instanceSimilarity: the two frames differ in image size");
  }
  if (current.image_size.width <= 0 || current.image_size.height <= 0) {
    throw std::invalid_argument("instanceSimilarity: the image size must be positive");
  }
  const double diag = std::hypot(current.image_size.width, current.image_size.height);
  const auto cur = staticBoxesByClass(current.boxes, options.dynamic_classes);
  const auto cand = staticBoxesByClass(candidate.boxes, options.dynamic_classes);

  InstanceSimilarity result;
  double total = 0.0;  // S_total
  for (const auto& [name, cur_boxes] : cur) {
    const auto it = cand.find(name);
    if (it == cand.end()) continue;
    const ClassScores scores = scoreClass(cur_boxes, it->second, diag, options);
    std::vector<bool> used_i(cur_boxes.size(), false), used_j(it->second.size(), false);
    matchSure(scores, options, used_i, used_j, result, total);
    const double threshold = dynamicThreshold(cur_boxes.size(), it->second.size(), options);
    matchGreedy(scores, threshold, used_i, used_j, result, total);
  }
  if (result.matches > 0) result.score = total / result.matches;
  return result;
}

}  // namespace ply_slam
