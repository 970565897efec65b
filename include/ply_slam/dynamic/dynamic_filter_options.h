#pragma once

#include "ply_slam/dynamic/delaunay_consistency_options.h"

namespace ply_slam {

// Label dynamic degree and the rejection rules (PAPER.md §3.2); keys of the `dynamic:` section.
struct DynamicFilterOptions {
  DelaunayConsistencyOptions consistency;
  double weight_threshold = 0.5;  // w_th: a feature with a larger dynamic weight is in DP
  double active_degree = 0.2;     // Th_min: r_d above which an active-class instance is dynamic
  double passive_degree = 0.5;    // Th_max: the stricter bound for passive classes
  int min_judged_features = 5;    // an active instance with fewer matched features is dynamic
};

}  // namespace ply_slam
