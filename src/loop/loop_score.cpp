#include "ply_slam/loop/loop_score.h"

namespace ply_slam {

double pointLineScore(double s_p, double s_l, double h_p, double h_l) {
  const double h = h_p + h_l;
  if (!(h > 0.0)) return 0.5 * (s_p + s_l);
  return (h_p / h) * s_p + (h_l / h) * s_l;
}

double finalLoopScore(double s_pl, double s_inst, const LoopOptions& options) {
  return options.point_line_weight * s_pl + options.instance_weight * s_inst;
}

LoopScore scoreLoopCandidate(double s_p, double s_l, const FeatureEntropy& query_entropy,
                             const InstanceFrame& query, const InstanceFrame& candidate,
                             const LoopOptions& options) {
  LoopScore score;
  score.point_line = pointLineScore(s_p, s_l, query_entropy.points, query_entropy.lines);
  const InstanceSimilarity instances = instanceSimilarity(query, candidate, options);
  score.instance = instances.score;
  score.instance_matches = instances.matches;
  score.final_score = finalLoopScore(score.point_line, score.instance, options);
  return score;
}

}  // namespace ply_slam
