#include "ply_slam/features/line_options_yaml.h"

namespace ply_slam {
namespace {

void readDetectionKeys(ConfigSection& s, LineOptions& l) {
  s.readWord("detector", l.detector, kLineDetectorWords, "must be auto, lsd or edlines");
  s.readPositive("lsd_scale", l.lsd_scale);
  if (l.lsd_scale > 1.0) s.fail("lsd_scale", "must be <= 1");
  s.read("refine_edges", l.refine_edges);
  s.readPositive("merge_angle_deg", l.merge_angle_deg);
  if (l.merge_angle_deg >= 90.0) s.fail("merge_angle_deg", "must be < 90");
  s.readPositive("merge_distance_px", l.merge_distance_px);
  s.read("merge_gap_px", l.merge_gap_px);
  if (l.merge_gap_px < 0.0) s.fail("merge_gap_px", "must be >= 0");
  s.readPositive("min_length_px", l.min_length_px);
  s.read("max_lines", l.max_lines);
  if (l.max_lines < 0) s.fail("max_lines", "must be >= 0 (0 = all)");
  s.readPositive("lbd_scale", l.lbd_scale);
  if (l.lbd_scale > 1.0) s.fail("lbd_scale", "must be <= 1");
  s.readPositive("lbd_band_width", l.lbd_band_width);
}

void readFittingKeys(ConfigSection& s, LineOptions& l) {
  s.read("depth_search_px", l.depth_search_px);
  if (l.depth_search_px < 0 || l.depth_search_px > 10)
    s.fail("depth_search_px", "must be within [0, 10]");
  s.readPositive("sigma_px", l.sigma_px);
  s.readPositive("chi2_inlier", l.chi2_inlier);
  s.readPositive("ransac_iterations", l.ransac_iterations);
  s.read("refit_rounds", l.refit_rounds);
  if (l.refit_rounds < 0) s.fail("refit_rounds", "must be >= 0");
  s.read("surface_band_px", l.surface_band_px);
  if (l.surface_band_px != 0 && (l.surface_band_px < 2 || l.surface_band_px > 20))
    s.fail("surface_band_px", "must be 0 (off) or within [2, 20]");
  s.readPositive("min_inlier_ratio", l.min_inlier_ratio);
  if (l.min_inlier_ratio > 1.0) s.fail("min_inlier_ratio", "must be <= 1");
  s.readPositive("min_length_m", l.min_length_m);
}

void readMatchingKeys(ConfigSection& s, LineOptions& l) {
  s.readPositive("max_descriptor_distance", l.max_descriptor_distance);
  s.readPositive("match_ratio", l.match_ratio);
  if (l.match_ratio > 1.0) s.fail("match_ratio", "must be <= 1");
  s.readPositive("match_angle_deg", l.match_angle_deg);
  s.readPositive("match_distance_px", l.match_distance_px);
}

}  // namespace

LineOptions readLineOptions(ConfigSection s) {
  LineOptions l;
  s.read("enabled", l.enabled);
  s.readWord("balance", l.balance, kLineBalanceWords, "must be paper or one");
  s.readPositive("residual_sigma_px", l.residual_sigma_px);
  readDetectionKeys(s, l);
  readFittingKeys(s, l);
  readMatchingKeys(s, l);
  s.rejectUnknownKeys();
  return l;
}

}  // namespace ply_slam
