#include "ply_slam/common/yaml_bounds.h"

#include <vector>

#include "ply_slam/common/config_error.h"

namespace ply_slam {
namespace {

// Walks the document as every reader after it will, aliases expanded, and stops at the
// first bound crossed instead of walking on.
class BoundedWalk {
 public:
  BoundedWalk(const std::string& source, const YamlBounds& bounds)
      : source_(source), bounds_(bounds) {}

  void visit(const YAML::Node& node) {
    for (const YAML::Node& ancestor : path_)
      if (ancestor.is(node)) fail("an alias lies inside the node it names (a cycle)");
    if (++nodes_ > bounds_.max_nodes)
      fail("more than " + std::to_string(bounds_.max_nodes) +
           " YAML nodes with the aliases expanded (aliases of aliases?)");
    if (static_cast<int>(path_.size()) >= bounds_.max_depth)
      fail("YAML nested deeper than " + std::to_string(bounds_.max_depth) + " levels");
    if (!node.IsSequence() && !node.IsMap()) return;
    path_.push_back(node);
    if (node.IsSequence())
      for (const YAML::Node& item : node) visit(item);
    else
      for (const auto& kv : node) {
        visit(kv.first);
        visit(kv.second);
      }
    path_.pop_back();
  }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    throw ConfigError("config " + source_ + ": " + what);
  }

  const std::string& source_;
  const YamlBounds& bounds_;
  std::vector<YAML::Node> path_;
  size_t nodes_ = 0;
};

}  // namespace

void checkYamlBounds(const YAML::Node& root, const std::string& source, const YamlBounds& bounds) {
  BoundedWalk(source, bounds).visit(root);
}

}  // namespace ply_slam
