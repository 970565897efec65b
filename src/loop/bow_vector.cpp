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

// Walks both (sorted) vectors' words once.
double unitBowScore(const BowVector& a, const BowVector& b) {
  double score = 0.0;
  auto i = a.begin(), j = b.begin();
  while (i != a.end() && j != b.end()) {
    if (i->first < j->first) {
      ++i;
    } else if (j->first < i->first) {
      ++j;
    } else {
      score += sharedWordScore(i++->second, j++->second);
    }
  }
  return score;
}

// With |x| = 1 for both, |x - y|_1 = 2 - 2 sum min(x_i, y_i) over the shared words.
double bowScore(const BowVector& v1, const BowVector& v2) {
  if (l1Norm(v1) <= 0.0 || l1Norm(v2) <= 0.0) return 0.0;
  BowVector a = v1, b = v2;
  normaliseL1(a);
  normaliseL1(b);
  return std::clamp(unitBowScore(a, b), 0.0, 1.0);
}

}  // namespace ply_slam
