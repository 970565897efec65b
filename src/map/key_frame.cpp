#include "ply_slam/map/key_frame.h"

namespace ply_slam {

int KeyFrame::trackedPoints(int min_observations) const {
  int n = 0;
  for (const auto& p : map_points)
    if (p && !p->bad && p->observations() >= min_observations) ++n;
  return n;
}

}  // namespace ply_slam
