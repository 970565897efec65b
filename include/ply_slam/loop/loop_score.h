#pragma once

#include <cmath>
#include <map>

#include "ply_slam/loop/instance_similarity.h"
#include "ply_slam/loop/loop_options.h"

namespace ply_slam {

// A bag-of-words vector: word id -> weight (DBoW2's BowVector has this shape).
using BowWeights = std::map<unsigned, double>;

// Information entropy of one frame's point or line features (H_p, H_l of PAPER.md §3.3).
// The paper does not define it; ours: the Shannon entropy (natural log) of the frame's BoW
// weights normalised to a distribution, p_w = |v_w| / sum |v|, H = -sum p_w ln p_w. A frame
// whose features fall into many distinct, evenly weighted words carries more information and
// gets more say in S_pl; one word or none gives 0. The base of the log cancels in the weights.
// Works with any container of (word, weight) pairs: BowVector (bow_vector.h) in LoopDetector,
// BowWeights in the tests.
template <typename BowVector>
double bowEntropy(const BowVector& bow) {
  double sum = 0.0;
  for (const auto& word : bow) sum += std::abs(static_cast<double>(word.second));
  if (!(sum > 0.0)) return 0.0;
  double entropy = 0.0;
  for (const auto& word : bow) {
    const double p = std::abs(static_cast<double>(word.second)) / sum;
    if (p > 0.0) entropy -= p * std::log(p);
  }
  return entropy;
}

// S_pl = H_p / (H_p + H_l) S_p + H_l / (H_p + H_l) S_l. When both entropies are 0 (no
// informative feature of either kind) the plain mean of S_p and S_l.
double pointLineScore(double s_p, double s_l, double h_p, double h_l);

// S_fin = w_pl S_pl + w_inst S_inst_fin (0.6 / 0.4 in the paper). S_inst_fin is 0 when no
// instance matched, as the paper defines it, so frames without objects score at most w_pl.
double finalLoopScore(double s_pl, double s_inst, const LoopOptions& options);

// H_p and H_l of a query keyframe: computed once per query, used for all its candidates.
struct FeatureEntropy {
  double points = 0.0;
  double lines = 0.0;
};

template <typename BowVector>
FeatureEntropy featureEntropy(const BowVector& point_bow, const BowVector& line_bow) {
  return {bowEntropy(point_bow), bowEntropy(line_bow)};
}

// Every score of one query-candidate pair, for logging and precision-recall curves.
struct LoopScore {
  double point_line = 0.0;  // S_pl
  double instance = 0.0;    // S_inst_fin
  int instance_matches = 0;
  double final_score = 0.0;  // S_fin
};

// S_fin of a candidate from its BoW similarities S_p, S_l (a BoW database computes them), the
// query's entropies and both keyframes' instances.
LoopScore scoreLoopCandidate(double s_p, double s_l, const FeatureEntropy& query_entropy,
                             const InstanceFrame& query, const InstanceFrame& candidate,
                             const LoopOptions& options);

}  // namespace ply_slam
