#pragma once

#include <memory>
#include <unordered_map>
#include <vector>

namespace ply_slam {

// Keyframes or landmarks by their id (what a copy of the map names them by).
template <typename T>
std::unordered_map<long, std::shared_ptr<T>> byId(const std::vector<std::shared_ptr<T>>& all) {
  std::unordered_map<long, std::shared_ptr<T>> by_id;
  for (const auto& x : all) by_id.emplace(x->id, x);
  return by_id;
}

}  // namespace ply_slam
