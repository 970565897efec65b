#pragma once

#include <algorithm>
#include <cstdint>
#include <map>
#include <utility>
#include <vector>

namespace ply_slam {

using WordId = uint32_t;
using NodeId = uint32_t;

// Bag of words of one image: (word, tf-idf weight), sorted by word id, one entry per word.
using BowVector = std::vector<std::pair<WordId, double>>;
// Direct index of one image: vocabulary node (some levels above the words) -> the indices of
// the image's features under it. Features under different nodes are unlikely to match.
using FeatureVector = std::map<NodeId, std::vector<int>>;

// Scales the weights to unit L1 norm (a vector of zero norm is left as it is).
void normaliseL1(BowVector& v);
// One shared word's share of the L1 score of two bags at unit L1 norm with weights >= 0.
inline double sharedWordScore(double a, double b) { return std::min(a, b); }
// The L1 score of two bags already at unit L1 norm: sharedWordScore summed over the words both
// hold, in word order. BowDatabase sums the same terms in the same order from its inverted
// index, so its scores are these to the bit.
double unitBowScore(const BowVector& a, const BowVector& b);
// Gálvez-López & Tardós's L1 score: 1 - 0.5 |v1/|v1| - v2/|v2||_1, in [0, 1]: 1 for the same
// words in the same proportions, 0 for no shared word (and when either vector is empty). For
// tf-idf weights (>= 0) it is unitBowScore of the two bags scaled to unit L1 norm.
double bowScore(const BowVector& v1, const BowVector& v2);

}  // namespace ply_slam
