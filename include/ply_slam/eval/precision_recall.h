#pragma once

#include <vector>

namespace ply_slam {

// One decision a detector can make: its score (it fires when score >= the threshold) and
// whether firing would be right.
struct ScoredDecision {
  double score = 0.0;
  bool correct = false;
};

// The detector at one threshold.
struct PrPoint {
  double threshold = 0.0;
  long detections = 0;      // decisions with score >= threshold
  long true_positives = 0;  // of them, correct
  double precision = 1.0;   // true_positives / detections; 1 when nothing fires
  double recall = 0.0;      // true_positives / positives
};

// A precision-recall curve over every threshold that changes the result.
struct PrCurve {
  long positives = 0;              // what a perfect detector would find (recall's denominator)
  std::vector<PrPoint> points;     // thresholds from high to low
  double average_precision = 0.0;  // area under the curve: sum over points of dRecall * precision
  double recall_at_full_precision = 0.0;     // best recall of a threshold with precision 1
  double threshold_at_full_precision = 0.0;  // the lowest such threshold (inf: none)
};

// The curve of `decisions` when `positives` things are to be found (a correct decision finds
// one; positives may exceed the correct decisions: what no decision finds is missed). Ties in
// score fire together. Throws std::invalid_argument when more decisions are correct than
// there are positives.
PrCurve precisionRecall(std::vector<ScoredDecision> decisions, long positives);

}  // namespace ply_slam
