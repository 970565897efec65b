#include "ply_slam/eval/precision_recall.h"

#include <algorithm>
#include <limits>
#include <stdexcept>

namespace ply_slam {

PrCurve precisionRecall(std::vector<ScoredDecision> decisions, long positives) {
  long correct = 0;
  for (const ScoredDecision& d : decisions) correct += d.correct;
  if (correct > positives)
    throw std::invalid_argument("precisionRecall: more correct decisions than positives");
  std::sort(decisions.begin(), decisions.end(),
            [](const ScoredDecision& a, const ScoredDecision& b) { return a.score > b.score; });
  PrCurve curve;
  curve.positives = positives;
  curve.threshold_at_full_precision = std::numeric_limits<double>::infinity();
  PrPoint p;
  double previous_recall = 0.0;
  for (size_t i = 0; i < decisions.size(); ++i) {
    ++p.detections;
    p.true_positives += decisions[i].correct;
    // Equal scores cannot be told apart by any threshold: one point for all of them.
    if (i + 1 < decisions.size() && decisions[i + 1].score == decisions[i].score) continue;
    p.threshold = decisions[i].score;
    p.precision = static_cast<double>(p.true_positives) / p.detections;
    p.recall = positives > 0 ? static_cast<double>(p.true_positives) / positives : 0.0;
    curve.average_precision += (p.recall - previous_recall) * p.precision;
    previous_recall = p.recall;
    if (p.precision == 1.0 && p.recall >= curve.recall_at_full_precision) {
      curve.recall_at_full_precision = p.recall;
      curve.threshold_at_full_precision = p.threshold;
    }
    curve.points.push_back(p);
  }
  return curve;
}

}  // namespace ply_slam
