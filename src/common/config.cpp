#include "ply_slam/common/config.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>
#include <sstream>

#include "ply_slam/common/camera_check.h"
#include "ply_slam/common/config_section.h"
#include "ply_slam/dense/occupancy_grid_options_yaml.h"
#include "ply_slam/loop/loop_options_yaml.h"
#include "ply_slam/mapping/culling_options_yaml.h"
#include "ply_slam/mapping/loop_correction_options_yaml.h"

namespace ply_slam {
namespace {

using Section = ConfigSection;

void readCamera(Section s, PinholeCamera& c) {
  s.readPositive("fx", c.fx, true);
  s.readPositive("fy", c.fy, true);
  s.readPositive("cx", c.cx, true);
  s.readPositive("cy", c.cy, true);
  s.readPositive("width", c.width, true);
  s.readPositive("height", c.height, true);
  std::vector<double> d;
  s.read("distortion", d);
  if (!d.empty() && d.size() != 4 && d.size() != 5)
    s.fail("distortion", "needs 4 or 5 coefficients (k1 k2 p1 p2 [k3])");
  if (!d.empty()) c.distortion = cv::Mat(d, true).reshape(1, 1);
  s.readPositive("depth_factor", c.depth_factor);
  s.readPositive("min_depth", c.min_depth);
  s.readPositive("max_depth", c.max_depth);
  s.read("rolling_shutter_readout", c.rolling_shutter_readout);
  Section n = s.child("depth_noise");
  n.read("alpha", c.depth_noise.alpha);
  n.read("beta", c.depth_noise.beta);
  n.read("gamma", c.depth_noise.gamma);
  n.read("delta", c.depth_noise.delta);
  n.rejectUnknownKeys();
  // The same checks as for intrinsics from a camera_info or a keyframe message.
  if (const auto problem = findCameraProblem(c)) s.fail(problem->key, problem->what);
  s.rejectUnknownKeys();
}

void readOrb(Section s, OrbParams& o) {
  s.readPositive("num_features", o.num_features);
  s.readPositive("num_levels", o.num_levels);
  if (o.num_levels > 32) s.fail("num_levels", "must be <= 32");
  s.readPositive("scale_factor", o.scale_factor);
  if (o.scale_factor <= 1.0) s.fail("scale_factor", "must be > 1");
  s.readPositive("fast_threshold", o.fast_threshold);
  s.readPositive("min_fast_threshold", o.min_fast_threshold);
  s.readPositive("grid_cell_size", o.grid_cell_size);
  s.readPositive("edge_threshold", o.edge_threshold);
  s.rejectUnknownKeys();
}

void readLines(Section s, LineParams& l) {
  s.read("enabled", l.enabled);
  s.read("balance", l.balance);
  if (l.balance != "paper" && l.balance != "one") s.fail("balance", "must be paper or one");
  s.readPositive("residual_sigma_px", l.residual_sigma_px);
  s.read("detector", l.detector);
  if (l.detector != "auto" && l.detector != "lsd" && l.detector != "edlines")
    s.fail("detector", "must be auto, lsd or edlines");
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
  s.readPositive("max_descriptor_distance", l.max_descriptor_distance);
  s.readPositive("match_ratio", l.match_ratio);
  if (l.match_ratio > 1.0) s.fail("match_ratio", "must be <= 1");
  s.readPositive("match_angle_deg", l.match_angle_deg);
  s.readPositive("match_distance_px", l.match_distance_px);
  s.rejectUnknownKeys();
}

void readTracking(Section s, TrackingParams& t) {
  s.readPositive("search_radius_px", t.search_radius_px);
  s.readPositive("max_descriptor_distance", t.max_descriptor_distance);
  s.readPositive("nn_ratio", t.nn_ratio);
  if (t.nn_ratio > 1.0) s.fail("nn_ratio", "must be <= 1");
  s.readPositive("min_tracked_points", t.min_tracked_points);
  s.readPositive("local_map_keyframes", t.local_map_keyframes);
  s.readPositive("chi2_outlier", t.chi2_outlier);
  s.readPositive("optimisation_rounds", t.optimisation_rounds);
  s.readPositive("keyframe_min_ratio", t.keyframe_min_ratio);
  s.readPositive("keyframe_max_frames", t.keyframe_max_frames);
  s.readPositive("keyframe_translation", t.keyframe_translation);
  s.readPositive("keyframe_rotation_deg", t.keyframe_rotation_deg);
  s.readPositive("max_prediction_error", t.max_prediction_error);
  s.readPositive("pnp_iterations", t.pnp_iterations);
  s.readPositive("pnp_reprojection_px", t.pnp_reprojection_px);
  s.readPositive("max_point_depth", t.max_point_depth);
  s.rejectUnknownKeys();
}

void readSegmentation(Section s, YoloParams& y) {
  s.read("model", y.model_path);
  s.read("classes", y.class_names_path);
  s.readPositive("input_width", y.input_width);
  s.readPositive("input_height", y.input_height);
  s.readPositive("score_threshold", y.score_threshold);
  s.readPositive("nms_threshold", y.nms_threshold);
  s.readPositive("mask_threshold", y.mask_threshold);
  if (y.score_threshold >= 1.f) s.fail("score_threshold", "must be < 1");
  if (y.nms_threshold > 1.f) s.fail("nms_threshold", "must be <= 1");
  if (y.mask_threshold >= 1.f) s.fail("mask_threshold", "must be < 1");
  s.rejectUnknownKeys();
}

void readDynamic(Section s, DynamicParams& d) {
  s.read("mode", d.mode);
  if (d.mode != "off" && d.mode != "geometric" && d.mode != "semantic" && d.mode != "full")
    s.fail("mode", "must be off, geometric, semantic or full");
  DynamicFilterParams& f = d.filter;
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
  s.read("active_classes", d.active_classes);
  s.read("passive_classes", d.passive_classes);
  for (const auto& name : d.active_classes)
    if (std::find(d.passive_classes.begin(), d.passive_classes.end(), name) !=
        d.passive_classes.end())
      s.fail("passive_classes", "'" + name + "' is also an active class");
  s.rejectUnknownKeys();
}

void readDense(Section s, DenseParams& d) {
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
  s.read("colour_mode", d.colour_mode);
  if (d.colour_mode != "class" && d.colour_mode != "rgb")
    s.fail("colour_mode", "must be class or rgb");
  s.read("palette", d.palette);
  s.rejectUnknownKeys();
}

// yaml-cpp keeps every copy of a repeated key and lookups find the first: a second value
// further down the file would be ignored without a word.
void rejectDuplicateKeys(const YAML::Node& node, const std::string& path,
                         const std::string& prefix) {
  if (node.IsSequence())
    for (const auto& item : node) rejectDuplicateKeys(item, path, prefix);
  if (!node.IsMap()) return;
  std::set<std::string> seen;
  for (const auto& kv : node) {
    const std::string key = kv.first.Scalar();
    if (!seen.insert(key).second)
      throw ConfigError("config " + path + ": " + prefix + key + " is given twice");
    rejectDuplicateKeys(kv.second, path, prefix + key + ".");
  }
}

// Every check of loadConfig, on a parsed document; `path` names it in errors.
SystemConfig parseConfig(const YAML::Node& root, const std::string& path) {
  if (!root.IsMap()) throw ConfigError("config " + path + ": the top level must be a map");
  rejectDuplicateKeys(root, path, "");

  SystemConfig config;
  config.source_path = path;
  Section top(root, path, "");
  if (!root["camera"]) top.fail("camera", "section is required");
  readCamera(top.child("camera"), config.camera);
  readOrb(top.child("orb"), config.orb);
  readLines(top.child("lines"), config.lines);
  readSegmentation(top.child("segmentation"), config.segmentation);
  readTracking(top.child("tracking"), config.tracking);
  readDynamic(top.child("dynamic"), config.dynamic);
  readDense(top.child("dense"), config.dense);
  config.grid = readOccupancyGridOptions(top.child("grid"));
  config.loop = readLoopOptions(top.child("loop"));
  config.loop.depth_noise = config.camera.depth_noise;
  config.loop_correction = readLoopCorrectionOptions(top.child("loop_correction"));
  config.culling = readCullingOptions(top.child("culling"));
  top.rejectUnknownKeys();
  return config;
}

}  // namespace

SystemConfig loadConfig(const std::string& path) {
  if (std::filesystem::is_directory(path))
    throw ConfigError("config " + path + ": is a directory, not a YAML file");
  YAML::Node root;
  try {
    root = YAML::LoadFile(path);
  } catch (const YAML::BadFile&) {
    throw ConfigError("config " + path + ": cannot open the file");
  } catch (const YAML::Exception& e) {
    throw ConfigError("config " + path + ": not valid YAML: " + e.what());
  } catch (const std::exception& e) {  // a read error of the stream (libstdc++'s words)
    throw ConfigError("config " + path + ": cannot read the file: " + e.what());
  }
  return parseConfig(root, path);
}

SystemConfig loadConfigFromString(const std::string& yaml_text, const std::string& source_name) {
  YAML::Node root;
  try {
    root = YAML::Load(yaml_text);
  } catch (const YAML::Exception& e) {
    throw ConfigError("config " + source_name + ": not valid YAML: " + e.what());
  }
  return parseConfig(root, source_name);
}

}  // namespace ply_slam
