#include "ply_slam/map/key_frame.h"

#include <algorithm>

namespace ply_slam {

std::shared_ptr<KeyFrame> KeyFrame::unlinkedCopy() const {
  auto copy = std::make_shared<KeyFrame>(*this);
  copy->map_points.assign(map_points.size(), nullptr);
  copy->map_lines.assign(map_lines.size(), nullptr);
  copy->covisibility.clear();
  copy->parent = nullptr;
  return copy;
}

int KeyFrame::trackedPoints(int min_observations) const {
  int n = 0;
  for (const auto& p : map_points)
    if (p && !p->bad && p->observations() >= min_observations) ++n;
  return n;
}

std::vector<KeyFrame*> KeyFrame::bestCovisible(size_t n) const {
  std::vector<std::pair<int, KeyFrame*>> ranked;
  for (const auto& [kf, weight] : covisibility) ranked.emplace_back(weight, kf);
  std::sort(ranked.begin(), ranked.end(), [](const auto& a, const auto& b) {
    return a.first != b.first ? a.first > b.first : a.second->id < b.second->id;
  });
  std::vector<KeyFrame*> best;
  for (size_t i = 0; i < ranked.size() && i < n; ++i) best.push_back(ranked[i].second);
  return best;
}

KeyFrame* KeyFrame::bestOlderCovisible() const {
  for (KeyFrame* kf : bestCovisible(covisibility.size()))
    if (kf->id < id) return kf;
  return nullptr;
}

}  // namespace ply_slam
