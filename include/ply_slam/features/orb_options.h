#pragma once

namespace ply_slam {

// ORB extraction (the config's `orb:` section). The pyramid's layout (levels, scale factor) is
// also what landmarks' scale levels are predicted with, in tracking and mapping.
struct OrbOptions {
  int num_features = 1000;  // target over all pyramid levels
  int num_levels = 8;
  double scale_factor = 1.2;
  int fast_threshold = 20;     // FAST threshold tried first in every grid cell
  int min_fast_threshold = 7;  // retried in cells where the first one found nothing
  int grid_cell_size = 32;     // px; corners are spread by cell, then by quadtree
  int edge_threshold = 19;     // px kept free at the border (descriptor patch)
};

}  // namespace ply_slam
