#include "ply_slam/loop/loop_options_yaml.h"

#include <set>
#include <stdexcept>
#include <string>

namespace ply_slam {
namespace {

// Reads keys of one map node, remembering them so that misspelt keys can be reported.
class LoopSection {
 public:
  explicit LoopSection(const YAML::Node& node) : node_(node) {
    if (present() && !node_.IsMap()) throw std::runtime_error("loop: must be a map of keys");
  }

  // value stays at its default when the key is absent; otherwise it must lie in [lo, hi].
  template <typename T>
  void read(const std::string& key, T& value, T lo, T hi) {
    used_.insert(key);
    if (!present() || !node_[key]) return;
    try {
      value = node_[key].as<T>();
    } catch (const YAML::Exception&) {
      fail(key, "has the wrong type");
    }
    if (!(value >= lo && value <= hi)) {
      fail(key, "must lie in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
    }
  }

  // A flag or a text: any value of the type.
  template <typename T>
  void readValue(const std::string& key, T& value) {
    used_.insert(key);
    if (!present() || !node_[key]) return;
    try {
      value = node_[key].as<T>();
    } catch (const YAML::Exception&) {
      fail(key, "has the wrong type");
    }
  }

  void readList(const std::string& key, std::vector<std::string>& value) {
    used_.insert(key);
    if (!present() || !node_[key]) return;
    if (!node_[key].IsSequence()) fail(key, "must be a list of class names");
    value = node_[key].as<std::vector<std::string>>();
  }

  void rejectUnknownKeys() const {
    if (!present()) return;
    for (const auto& kv : node_) {
      const auto key = kv.first.as<std::string>();
      if (!used_.count(key)) fail(key, "is not a known key");
    }
  }

  [[noreturn]] static void fail(const std::string& key, const std::string& what) {
    throw std::runtime_error("loop." + key + " " + what);
  }

 private:
  bool present() const { return node_.IsDefined() && !node_.IsNull(); }

  const YAML::Node node_;
  std::set<std::string> used_;
};

constexpr double kHuge = 1e12;

void readGeneralKeys(LoopSection& s, LoopOptions& o) {
  s.readValue("enabled", o.enabled);
  s.readValue("orb_vocabulary", o.orb_vocabulary);
  s.readValue("lbd_vocabulary", o.lbd_vocabulary);
}

void readInstanceKeys(LoopSection& s, LoopOptions& o) {
  s.read("position_weight", o.position_weight, 0.0, 1.0);
  s.read("iou_weight", o.iou_weight, 0.0, 1.0);
  s.read("iou_epsilon", o.iou_epsilon, 0.0, 1.0);
  s.read("spatial_consistency_threshold", o.spatial_consistency_threshold, 0.0, 1.0);
  s.read("consistency_boost", o.consistency_boost, 0.0, 1.0);
  s.read("consistency_penalty", o.consistency_penalty, 0.0, 1.0);
  s.read("sure_position", o.sure_position, 0.0, 1.0);
  s.read("dyna_ceiling", o.dyna_ceiling, 0.0, 1.0);
  s.read("dyna_floor", o.dyna_floor, 0.0, 1.0);
  s.read("dyna_step", o.dyna_step, 0.0, 1.0);
  s.readList("dynamic_classes", o.dynamic_classes);
}

void readSelectionKeys(LoopSection& s, LoopOptions& o) {
  s.read("point_line_weight", o.point_line_weight, 0.0, 1.0);
  s.read("instance_weight", o.instance_weight, 0.0, 1.0);
  s.read("min_normalised_score", o.min_normalised_score, 0.0, kHuge);
  s.read("consistency", o.consistency, 1, 1000);
  s.read("min_covisible_shared", o.min_covisible_shared, 1, 1000000);
  s.read("min_candidate_age_s", o.min_candidate_age_s, 0.0, kHuge);
}

void readGeometricKeys(LoopSection& s, LoopOptions& o) {
  s.read("direct_index_levels_up", o.direct_index_levels_up, 0, 20);
  s.read("match_max_distance", o.match_max_distance, 0, 256);
  s.read("match_ratio", o.match_ratio, 0.0, 1.0);
  s.read("ransac_iterations", o.ransac_iterations, 1, 1000000);
  s.read("ransac_seed", o.ransac_seed, 0u, ~0u);
  s.read("refine_iterations", o.refine_iterations, 0, 1000);
  s.read("inlier_sigma_factor", o.inlier_sigma_factor, 0.0, kHuge);
  s.read("min_inlier_distance", o.min_inlier_distance, 0.0, kHuge);
  s.read("min_inliers_3d", o.min_inliers_3d, 3, 1000000);
  s.read("reprojection_px", o.reprojection_px, 0.0, kHuge);
  s.read("min_reprojection_inliers", o.min_reprojection_inliers, 0, 1000000);
}

}  // namespace

LoopOptions loopOptionsFromYaml(const YAML::Node& loop_section) {
  LoopOptions options;
  LoopSection section(loop_section);
  readGeneralKeys(section, options);
  readInstanceKeys(section, options);
  readSelectionKeys(section, options);
  readGeometricKeys(section, options);
  section.rejectUnknownKeys();
  if (options.dyna_floor > options.dyna_ceiling) {
    LoopSection::fail("dyna_floor", "must not exceed loop.dyna_ceiling");
  }
  return options;
}

}  // namespace ply_slam
