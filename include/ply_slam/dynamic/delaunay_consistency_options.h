#pragma once

namespace ply_slam {

// The Delaunay topology check (dynamic module, PAPER.md §3.2); keys of the `dynamic:` section.
struct DelaunayConsistencyOptions {
  double sigma_factor = 3.0;  // an edge is inconsistent when its length changes > k sigma
  double min_change = 0.01;   // m; and by at least this much (unmodelled errors)
  double pixel_sigma = 1.0;   // px; a feature's pixel noise (its depth too, where depth slopes)
  // Features joined by consistent edges form rigid bodies; the largest (the static scene)
  // fixes the camera's motion. Only when it has fewer than 3 features to fit that motion by:
  // those of a body smaller than this share of the largest get weight 1.
  double minority_share = 0.5;
  // m; the predicted camera motion carries a static feature within this of where it is (the
  // constant-velocity prediction errs by ~1 cm over the baseline; a walker moves 5-15 cm).
  double prediction_tolerance = 0.03;
};

}  // namespace ply_slam
