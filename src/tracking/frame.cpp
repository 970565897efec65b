#include "ply_slam/tracking/frame.h"

namespace ply_slam {

int Frame::numMatches() const {
  int n = 0;
  for (size_t i = 0; i < map_points.size(); ++i) n += map_points[i] && !outlier[i];
  return n;
}

void Frame::clearMatches() {
  std::fill(map_points.begin(), map_points.end(), nullptr);
  std::fill(outlier.begin(), outlier.end(), false);
}

}  // namespace ply_slam
