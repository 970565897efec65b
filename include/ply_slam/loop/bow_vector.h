#pragma once

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
// Gálvez-López & Tardós's L1 score: 1 - 0.5 |v1/|v1| - v2/|v2||_1, in [0, 1]: 1 for the same
// words in the same proportions, 0 for no shared word (and when either vector is empty).
double bowScore(const BowVector& v1, const BowVector& v2);

}  // namespace ply_slam
