#include "ply_slam/dense/dense_options_yaml.h"

namespace ply_slam {

DenseOptions readDenseOptions(ConfigSection s) {
  DenseOptions d;
  s.read("enabled", d.enabled);
  // Beyond these the loops over pixels overflow and OctoMap's keys cannot cover a room.
  s.readInRange("stride", d.stride, 1, 1000);
  s.readPositive("min_depth", d.min_depth);
  s.readPositive("max_depth", d.max_depth);
  if (d.max_depth <= d.min_depth) s.fail("max_depth", "must be > min_depth");
  s.readInRange("voxel_size", d.voxel_size, 1e-4, 10.0);
  s.read("dilation_px", d.dilation_px);
  if (d.dilation_px < 0 || d.dilation_px > 50) s.fail("dilation_px", "must be within [0, 50]");
  s.readInRange("octree_resolution", d.octree_resolution, 1e-3, 10.0);
  s.read("octree_occupancy", d.octree_occupancy);
  if (!(d.octree_occupancy >= 0.5 && d.octree_occupancy < 0.97))
    s.fail("octree_occupancy", "must be within [0.5, 0.97)");
  s.read("ray_margin", d.ray_margin);
  if (!(d.ray_margin >= 0.0 && d.ray_margin <= 1.0))
    s.fail("ray_margin", "must be within [0, 1] m");
  s.read("octree_filter", d.octree_filter);
  s.readWord("colour_mode", d.colour_mode, kOctreeColourModeWords, "must be class or rgb");
  s.read("palette", d.palette);
  s.rejectUnknownKeys();
  return d;
}

}  // namespace ply_slam
