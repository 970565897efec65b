#include "ply_slam/dynamic/delaunay_consistency.h"

#include <cmath>
#include <map>
#include <opencv2/imgproc.hpp>

namespace ply_slam {

bool DelaunayConsistency::inconsistent(const FeatureCorrespondence& a,
                                       const FeatureCorrespondence& b) const {
  const double before = (a.previous - b.previous).norm();
  const double after = (a.current - b.current).norm();
  // The length's variance: each endpoint's depth noise, in both frames.
  const double variance = noise_.variance(a.previous.z()) + noise_.variance(b.previous.z()) +
                          noise_.variance(a.current.z()) + noise_.variance(b.current.z());
  const double allowed = std::max(params_.min_change, params_.sigma_factor * std::sqrt(variance));
  return std::abs(after - before) > allowed;
}

std::vector<double> DelaunayConsistency::weights(const std::vector<FeatureCorrespondence>& features,
                                                 int width, int height) const {
  std::vector<double> weight(features.size(), 0.0);
  if (features.size() < 3) return weight;

  // Subdiv2D reports edges by position: map positions back to features (a duplicate
  // position keeps the first feature).
  cv::Subdiv2D subdiv(cv::Rect(-1, -1, width + 2, height + 2));
  std::map<std::pair<float, float>, size_t> at;
  for (size_t i = 0; i < features.size(); ++i) {
    const cv::Point2f p(static_cast<float>(features[i].pixel.x()),
                        static_cast<float>(features[i].pixel.y()));
    if (p.x < -1 || p.y < -1 || p.x >= width + 1 || p.y >= height + 1) continue;
    if (!at.emplace(std::make_pair(p.x, p.y), i).second) continue;
    subdiv.insert(p);
  }

  std::vector<int> edges_of(features.size(), 0), bad_of(features.size(), 0);
  std::vector<cv::Vec4f> edges;
  subdiv.getEdgeList(edges);
  for (const auto& e : edges) {
    // Edges to the outer virtual vertices find no feature and are skipped.
    const auto a = at.find({e[0], e[1]}), b = at.find({e[2], e[3]});
    if (a == at.end() || b == at.end()) continue;
    // A broken edge says one of its ends moved, not which: both get the vote.
    const bool bad = inconsistent(features[a->second], features[b->second]);
    for (size_t f : {a->second, b->second}) {
      ++edges_of[f];
      bad_of[f] += bad;
    }
  }
  for (size_t i = 0; i < features.size(); ++i)
    if (edges_of[i] > 0) weight[i] = static_cast<double>(bad_of[i]) / edges_of[i];
  return weight;
}

}  // namespace ply_slam
