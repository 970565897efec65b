#include "ply_slam/dynamic/dynamic_options_yaml.h"

#include <algorithm>

namespace ply_slam {
namespace {

void readFilterKeys(ConfigSection& s, DynamicFilterOptions& f) {
  s.readPositive("sigma_factor", f.consistency.sigma_factor);
  s.read("min_change", f.consistency.min_change);
  if (f.consistency.min_change < 0) s.fail("min_change", "must be >= 0");
  s.read("weight_threshold", f.weight_threshold);
  if (f.weight_threshold < 0 || f.weight_threshold >= 1)
    s.fail("weight_threshold", "must be in [0, 1)");
  s.read("active_degree", f.active_degree);
  if (f.active_degree < 0 || f.active_degree >= 1) s.fail("active_degree", "must be in [0, 1)");
  s.read("passive_degree", f.passive_degree);
  if (f.passive_degree < f.active_degree || f.passive_degree >= 1)
    s.fail("passive_degree", "must be in [active_degree, 1)");
  s.readPositive("pixel_sigma", f.consistency.pixel_sigma);
  s.read("minority_share", f.consistency.minority_share);
  if (f.consistency.minority_share < 0 || f.consistency.minority_share > 1)
    s.fail("minority_share", "must be in [0, 1]");
  s.readPositive("prediction_tolerance", f.consistency.prediction_tolerance);
  s.read("min_judged_features", f.min_judged_features);
  if (f.min_judged_features < 1) s.fail("min_judged_features", "must be >= 1");
}

void readRejectorKeys(ConfigSection& s, DynamicOptions& d) {
  s.read("mask_dilation_px", d.mask_dilation_px);
  if (d.mask_dilation_px < 0 || d.mask_dilation_px > 50)
    s.fail("mask_dilation_px", "must be in [0, 50]");
  s.read("baseline_frames", d.baseline_frames);
  if (d.baseline_frames < 1 || d.baseline_frames > 30)
    s.fail("baseline_frames", "must be in [1, 30]");
  s.read("carry_frames", d.carry_frames);
  if (d.carry_frames < 0 || d.carry_frames > 30) s.fail("carry_frames", "must be in [0, 30]");
  s.readPositive("match_radius_px", d.match_radius_px);
  s.readPositive("max_descriptor_distance", d.max_descriptor_distance);
}

void readClassKeys(ConfigSection& s, DynamicOptions& d) {
  s.read("active_classes", d.active_classes);
  s.read("passive_classes", d.passive_classes);
  for (const auto& name : d.active_classes)
    if (std::find(d.passive_classes.begin(), d.passive_classes.end(), name) !=
        d.passive_classes.end())
      s.fail("passive_classes", "'" + name + "' is also an active class");
}

}  // namespace

DynamicOptions readDynamicOptions(ConfigSection s) {
  DynamicOptions d;
  s.readWord("mode", d.mode, kDynamicModeWords, "must be off, geometric, semantic or full");
  readFilterKeys(s, d.filter);
  readRejectorKeys(s, d);
  readClassKeys(s, d);
  s.rejectUnknownKeys();
  return d;
}

}  // namespace ply_slam
