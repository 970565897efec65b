#pragma once

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <set>
#include <string>
#include <type_traits>
#include <vector>

#include "ply_slam/common/config_error.h"
#include "ply_slam/common/enum_words.h"

namespace ply_slam {

// Reads one YAML map section; remembers which keys were read so that misspelt keys are
// reported instead of silently falling back to defaults.
class ConfigSection {
 public:
  ConfigSection(const YAML::Node& node, std::string file, std::string name)
      : node_(node), file_(std::move(file)), name_(std::move(name)) {
    if (node_.IsDefined() && !node_.IsNull() && !node_.IsMap())
      throw ConfigError(where() + name_ + " must be a map of keys");
  }

  template <typename T>
  void read(const std::string& key, T& value, bool required = false) {
    used_.insert(key);
    // A section that is absent leaves every key at its default.
    const YAML::Node v = get(key);
    if (!v.IsDefined() || v.IsNull()) {
      if (required) fail(key, "is required");
      return;
    }
    try {
      value = v.as<T>();
    } catch (const YAML::Exception&) {
      fail(key, "has the wrong type (value '" + YAML::Dump(v) + "')");
    }
    // YAML reads .nan and .inf as numbers; no setting may be one.
    if (!allFinite(value)) fail(key, "must be a finite number (value '" + YAML::Dump(v) + "')");
  }

  template <typename T>
  void readPositive(const std::string& key, T& value, bool required = false) {
    read(key, value, required);
    if (!(value > T(0))) fail(key, "must be > 0");
  }

  // A value that stays at its default when absent, otherwise must lie in [lo, hi].
  template <typename T>
  void readInRange(const std::string& key, T& value, T lo, T hi) {
    read(key, value);
    if (!(value >= lo && value <= hi))
      fail(key, "must lie in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
  }

  // A word of `words` (absent: value unchanged); another word fails with `what` ("must be ...").
  template <typename Enum, std::size_t N>
  void readWord(const std::string& key, Enum& value, const EnumWord<Enum> (&words)[N],
                const std::string& what) {
    std::string word = wordOf(words, value);
    read(key, word);
    if (!valueOf(words, word, value)) fail(key, what);
  }

  void readList(const std::string& key, std::vector<std::string>& value) {
    const YAML::Node v = get(key);
    if (v.IsDefined() && !v.IsNull() && !v.IsSequence()) {
      used_.insert(key);
      fail(key, "must be a list");
    }
    read(key, value);
  }

  ConfigSection child(const std::string& key) {
    used_.insert(key);
    return ConfigSection(get(key), file_, path(key));
  }

  // Every key present in the file must have been read.
  void rejectUnknownKeys() const {
    if (!node_.IsDefined() || node_.IsNull()) return;
    for (const auto& kv : node_) {
      // A list or map as a key (YAML's "? " form) is a mistake to report, not to convert.
      if (!kv.first.IsScalar()) fail("'" + YAML::Dump(kv.first) + "'", "is not a key name");
      const auto key = kv.first.as<std::string>();
      if (!used_.count(key)) fail(key, "is not a known key");
    }
  }

  [[noreturn]] void fail(const std::string& key, const std::string& what) const {
    throw ConfigError(where() + path(key) + " " + what);
  }

  // The value under key, undefined when this section or the key is absent. Read through a
  // const node: yaml-cpp's non-const operator[] would insert the key.
  YAML::Node get(const std::string& key) const {
    const YAML::Node& node = node_;
    return node.IsDefined() && node.IsMap() ? node[key] : YAML::Node(YAML::NodeType::Undefined);
  }

  std::string path(const std::string& key) const { return name_.empty() ? key : name_ + "." + key; }

 private:
  template <typename T>
  static bool allFinite(const T& value) {
    if constexpr (std::is_floating_point_v<T>) return std::isfinite(value);
    return true;
  }
  template <typename T>
  static bool allFinite(const std::vector<T>& values) {
    for (const T& v : values)
      if (!allFinite(v)) return false;
    return true;
  }

  // The file the section came from, when it came from one.
  std::string where() const { return file_.empty() ? "config: " : "config " + file_ + ": "; }

  YAML::Node node_;
  std::string file_, name_;
  std::set<std::string> used_;
};

}  // namespace ply_slam
