#include "ply_slam/features/orb_options_yaml.h"

namespace ply_slam {
namespace {

// px. OpenCV's default is 31; a border of thousands left no pixel to extract from and tracked
// nothing without a word (issue #53).
constexpr int kMaxOrbEdgeThreshold = 100;

}  // namespace

OrbOptions readOrbOptions(ConfigSection s) {
  OrbOptions o;
  s.readPositive("num_features", o.num_features);
  s.readPositive("num_levels", o.num_levels);
  if (o.num_levels > 32) s.fail("num_levels", "must be <= 32");
  s.readPositive("scale_factor", o.scale_factor);
  if (o.scale_factor <= 1.0) s.fail("scale_factor", "must be > 1");
  s.readPositive("fast_threshold", o.fast_threshold);
  s.readPositive("min_fast_threshold", o.min_fast_threshold);
  s.readPositive("grid_cell_size", o.grid_cell_size);
  s.readInRange("edge_threshold", o.edge_threshold, 1, kMaxOrbEdgeThreshold);
  s.rejectUnknownKeys();
  return o;
}

}  // namespace ply_slam
