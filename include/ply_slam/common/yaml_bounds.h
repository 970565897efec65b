#pragma once

#include <yaml-cpp/yaml.h>

#include <cstddef>
#include <string>

namespace ply_slam {

// yaml-cpp does not copy an aliased node, it shares it: an alias inside its own anchor
// (`a: &x [*x]`) makes a cycle, and aliases of aliases ("billion laughs", 20 kB) a tree of 10^9
// nodes. Every later walk (the duplicate-key check, the key readers, YAML::Dump) would recurse
// for ever or for minutes. The configs we ship have a few hundred nodes, 5 levels deep.
struct YamlBounds {
  size_t max_nodes = 100000;  // nodes with the aliases expanded, keys counted
  int max_depth = 64;
};

// Throws ConfigError naming `source` ("config FILE: ...") when an alias lies inside the node it
// names, or the document, its aliases expanded, is deeper or larger than `bounds`.
void checkYamlBounds(const YAML::Node& root, const std::string& source,
                     const YamlBounds& bounds = YamlBounds{});

}  // namespace ply_slam
