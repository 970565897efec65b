#include "ply_slam/loop/bow_vector.h"

#include <algorithm>
#include <cmath>

namespace ply_slam {

namespace {

double l1Norm(const BowVector& v) {
  double norm = 0.0;
  for (const auto& [word, weight] : v) norm += std::abs(weight);
  return norm;
}

}  // namespace

void normaliseL1(BowVector& v) {
  const double norm = l1Norm(v);
  if (norm <= 0.0) return;
  for (auto& entry : v) entry.second /= norm;
}

// Walks the union of both (sorted) vectors' words once. For non-negative weights at unit norm
// this equals the sum of min(a_i, b_i) over the shared words (BowDatabase's shortcut).
double bowScore(const BowVector& v1, const BowVector& v2) {
  const double n1 = l1Norm(v1), n2 = l1Norm(v2);
  if (n1 <= 0.0 || n2 <= 0.0) return 0.0;
  double distance = 0.0;
  auto a = v1.begin(), b = v2.begin();
  while (a != v1.end() || b != v2.end()) {
    if (b == v2.end() || (a != v1.end() && a->first < b->first)) {
      distance += std::abs(a++->second) / n1;
    } else if (a == v1.end() || b->first < a->first) {
      distance += std::abs(b++->second) / n2;
    } else {
      distance += std::abs(a++->second / n1 - b++->second / n2);
    }
  }
  return std::clamp(1.0 - 0.5 * distance, 0.0, 1.0);
}

}  // namespace ply_slam
