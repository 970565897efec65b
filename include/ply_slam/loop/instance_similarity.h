#pragma once

#include <cstddef>
#include <optional>
#include <vector>

#include "ply_slam/loop/loop_options.h"
#include "ply_slam/semantic/instance_box.h"

namespace ply_slam {

// S_inst_fin of PAPER.md §3.3 and how many instance pairs produced it.
struct InstanceSimilarity {
  double score = 0.0;  // S_total / N_match; 0 when nothing matched
  int matches = 0;     // N_match, summed over classes
};

// Instance similarity between the current and a candidate keyframe (PAPER.md §3.3):
// dynamic classes dropped, the rest grouped by class; per class the n1 x n2 matrix
// S_inst = w_pos S_pos + w_iou S_IoU, adjusted by spatial consistency, then matched in two
// steps (sure matches by S_pos, then greedy best pairs above Th_dyna). N_match and S_total are
// summed over all classes. Both frames must have the same image size (one camera); otherwise
// std::invalid_argument.
InstanceSimilarity instanceSimilarity(const InstanceFrame& current, const InstanceFrame& candidate,
                                      const LoopOptions& options);

// Th_dyna = max(floor, min(ceiling, ceiling - step min(n1, n2))). n1, n2 are the sizes of one
// class's matrix (instances of that class in each frame): the paper builds and matches one
// matrix per class, so "the number of instances" is read per class.
double dynamicThreshold(size_t n1, size_t n2, const LoopOptions& options);

// S_aver of two neighbourhood vectors (each: diag-normalised distances from an instance to the
// other instances of its class in its own frame). Our definition, the paper gives none: both
// sorted ascending, compared over the shorter length m as 1 - (1/m) sum_k |a_k - b_k|, so the
// nearest neighbours are compared with each other. nullopt when either vector is empty (an
// instance alone in its class): no evidence either way, S_inst is left unadjusted.
std::optional<double> neighbourhoodSimilarity(std::vector<double> a, std::vector<double> b);

}  // namespace ply_slam
