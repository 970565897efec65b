#include "ply_slam/system/system_config.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>
#include <sstream>
#include <vector>

#include "ply_slam/common/camera_check.h"
#include "ply_slam/common/config_section.h"
#include "ply_slam/common/yaml_bounds.h"
#include "ply_slam/dense/dense_options_yaml.h"
#include "ply_slam/dense/occupancy_grid_options_yaml.h"
#include "ply_slam/dynamic/dynamic_options_yaml.h"
#include "ply_slam/features/line_options_yaml.h"
#include "ply_slam/features/orb_options_yaml.h"
#include "ply_slam/io/input_file.h"
#include "ply_slam/loop/loop_options_yaml.h"
#include "ply_slam/mapping/culling_options_yaml.h"
#include "ply_slam/mapping/local_mapping_options_yaml.h"
#include "ply_slam/mapping/loop_correction_options_yaml.h"
#include "ply_slam/semantic/yolo_options_yaml.h"
#include "ply_slam/tracking/tracking_options_yaml.h"

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

// The node at a dotted key; undefined when a part is missing.
YAML::Node at(const YAML::Node& node, const std::string& dotted) {
  const size_t dot = dotted.find('.');
  const std::string part = dotted.substr(0, dot);
  if (!node.IsMap() || !node[part]) return YAML::Node(YAML::NodeType::Undefined);
  return dot == std::string::npos ? node[part] : at(node[part], dotted.substr(dot + 1));
}

bool sameScalar(const YAML::Node& a, const YAML::Node& b) {
  double x = 0, y = 0;
  if (YAML::convert<double>::decode(a, x) && YAML::convert<double>::decode(b, y)) return x == y;
  return a.Scalar() == b.Scalar();
}

// The dotted keys under `key` whose values differ (one missing in either counts).
void appendDifferingKeys(const YAML::Node& a, const YAML::Node& b, const std::string& key,
                         std::vector<std::string>& differ) {
  if (a.IsMap() && b.IsMap()) {
    std::set<std::string> keys;
    for (const auto& node : {a, b})
      for (const auto& kv : node) keys.insert(kv.first.Scalar());
    for (const std::string& k : keys)
      appendDifferingKeys(a[k] ? a[k] : YAML::Node(YAML::NodeType::Undefined),
                          b[k] ? b[k] : YAML::Node(YAML::NodeType::Undefined), key + "." + k,
                          differ);
    return;
  }
  bool same = a.Type() == b.Type();
  if (same && a.IsScalar()) same = sameScalar(a, b);
  if (same && a.IsSequence()) {
    same = a.size() == b.size();
    for (size_t i = 0; same && i < a.size(); ++i)
      same = a[i].IsScalar() && b[i].IsScalar() ? sameScalar(a[i], b[i])
                                                : YAML::Dump(a[i]) == YAML::Dump(b[i]);
  }
  if (!same) differ.push_back(key);
}

// Every check of loadConfig, on a parsed document; `path` names it in errors.
SystemConfig parseConfig(const YAML::Node& root, const std::string& path) {
  if (!root.IsMap()) throw ConfigError("config " + path + ": the top level must be a map");
  checkYamlBounds(root, path);  // before any walk: an alias cycle or bomb never ends one
  rejectDuplicateKeys(root, path, "");

  SystemConfig config;
  config.source_path = path;
  config.yaml = YAML::Dump(root);
  Section top(root, path, "");
  if (!root["camera"]) top.fail("camera", "section is required");
  readCamera(top.child("camera"), config.camera);
  config.orb = readOrbOptions(top.child("orb"));
  config.lines = readLineOptions(top.child("lines"));
  config.segmentation = readYoloOptions(top.child("segmentation"));
  config.tracking = readTrackingOptions(top.child("tracking"));
  config.mapping = readLocalMappingOptions(top.child("mapping"));
  config.mapping.window_keyframes = config.tracking.local_map_keyframes;
  config.mapping.chi2_outlier = config.tracking.chi2_outlier;
  config.dynamic = readDynamicOptions(top.child("dynamic"));
  config.dense = readDenseOptions(top.child("dense"));
  config.grid = readOccupancyGridOptions(top.child("grid"));
  config.loop = readLoopOptions(top.child("loop"));
  useCamera(config, config.camera);
  config.loop_correction = readLoopCorrectionOptions(top.child("loop_correction"));
  config.culling = readCullingOptions(top.child("culling"));
  top.rejectUnknownKeys();
  return config;
}

// The one document of a config: yaml-cpp's Load reads the first and drops the rest without a
// word, so a second document (after "---") would be ignored.
YAML::Node onlyDocument(const std::vector<YAML::Node>& documents, const std::string& name) {
  if (documents.size() > 1)
    throw ConfigError("config " + name + ": holds " + std::to_string(documents.size()) +
                      " YAML documents (separated by ---); a config is one");
  return documents.empty() ? YAML::Node() : documents.front();
}

}  // namespace

SystemConfig loadConfig(const std::string& path) {
  // A named pipe would block the open for ever, a directory fail with no name.
  if (const auto problem = specialFileProblem(path))
    throw ConfigError("config " + path + ": " + *problem);
  YAML::Node root;
  try {
    root = onlyDocument(YAML::LoadAllFromFile(path), path);
  } catch (const ConfigError&) {
    throw;
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
    root = onlyDocument(YAML::LoadAll(yaml_text), source_name);
  } catch (const YAML::Exception& e) {
    throw ConfigError("config " + source_name + ": not valid YAML: " + e.what());
  }
  return parseConfig(root, source_name);
}

MapperOptions mapperOptions(const SystemConfig& config) {
  MapperOptions o;
  o.local = config.mapping;
  o.culling = config.culling;
  o.loop = config.loop;
  o.loop_correction = config.loop_correction;
  o.orb = config.orb;
  o.lines = config.lines;
  o.max_point_depth = config.tracking.max_point_depth;
  o.mask_dilation_px = config.dynamic.mask_dilation_px;
  return o;
}

std::vector<std::string> mappingSettingsThatDiffer(const SystemConfig& a, const SystemConfig& b) {
  // Whole sections, or one key of a section: what mapperOptions reads, the ORB section included.
  static const char* const kMappingSideKeys[] = {"orb",
                                                 "lines",
                                                 "mapping",
                                                 "loop",
                                                 "loop_correction",
                                                 "culling",
                                                 "tracking.max_point_depth",
                                                 "tracking.local_map_keyframes",
                                                 "tracking.chi2_outlier",
                                                 "dynamic.mask_dilation_px"};
  const YAML::Node root_a = YAML::Load(a.yaml), root_b = YAML::Load(b.yaml);
  std::vector<std::string> differ;
  for (const std::string key : kMappingSideKeys)
    appendDifferingKeys(at(root_a, key), at(root_b, key), key, differ);
  return differ;
}

void useCamera(SystemConfig& config, const PinholeCamera& camera) {
  config.camera = camera;
  config.loop.depth_noise = camera.depth_noise;  // the place check weighs depths as the camera
}

}  // namespace ply_slam
