#include "ply_slam/tracking/frame.h"

namespace ply_slam {

int Frame::numMatches() const {
  int n = 0;
  for (size_t i = 0; i < map_points.size(); ++i) n += map_points[i] && !outlier[i];
  return n;
}

void Frame::setLines(FrameLines frame_lines) {
  lines = std::move(frame_lines);
  map_lines.assign(lines.size(), nullptr);
  line_outlier.assign(lines.size(), false);
}

int Frame::numLineMatches() const {
  int n = 0;
  for (size_t i = 0; i < map_lines.size(); ++i) n += map_lines[i] && !line_outlier[i];
  return n;
}

void Frame::clearMatches() {
  std::fill(map_points.begin(), map_points.end(), nullptr);
  std::fill(outlier.begin(), outlier.end(), false);
  std::fill(map_lines.begin(), map_lines.end(), nullptr);
  std::fill(line_outlier.begin(), line_outlier.end(), false);
}

}  // namespace ply_slam
