#include "ply_slam/loop/direct_index_matcher.h"

#include <algorithm>
#include <climits>

#include "ply_slam/common/hamming.h"
#include "ply_slam/features/best_two.h"

namespace ply_slam {

DirectIndexMatcher::DirectIndexMatcher(int max_distance, double ratio)
    : max_distance_(max_distance), ratio_(ratio) {}

std::vector<std::pair<int, int>> DirectIndexMatcher::match(const FeatureVector& features_a,
                                                           const cv::Mat& descriptors_a,
                                                           const FeatureVector& features_b,
                                                           const cv::Mat& descriptors_b) const {
  CV_Assert(descriptors_a.cols == descriptors_b.cols);
  const int bytes = descriptors_a.cols;
  // best_a[j]: the a matched to b's feature j and its distance.
  std::vector<std::pair<int, int>> best_a(descriptors_b.rows, {-1, INT_MAX});
  auto a = features_a.begin();
  auto b = features_b.begin();
  while (a != features_a.end() && b != features_b.end()) {  // both sorted by node
    if (a->first != b->first) {
      (a->first < b->first ? ++a : ++b);
      continue;
    }
    for (int i : a->second) {
      BestTwo best;
      for (int j : b->second)
        best.offer(
            hammingDistance(descriptors_a.ptr<uint8_t>(i), descriptors_b.ptr<uint8_t>(j), bytes),
            j);
      if (!best.accept(max_distance_, ratio_)) continue;
      auto& kept = best_a[best.index];
      if (best.best < kept.second) kept = {i, best.best};
    }
    ++a;
    ++b;
  }
  std::vector<std::pair<int, int>> matches;
  for (int j = 0; j < descriptors_b.rows; ++j)
    if (best_a[j].first >= 0) matches.emplace_back(best_a[j].first, j);
  std::sort(matches.begin(), matches.end());
  return matches;
}

}  // namespace ply_slam
