#pragma once

#include <climits>

namespace ply_slam {

// The smallest and second-smallest descriptor distance offered, and where the smallest was:
// a match is kept only when it is good and clearly better than the runner-up.
struct BestTwo {
  int best = INT_MAX;
  int second = INT_MAX;
  long index = -1;

  void offer(int distance, long i) {
    if (distance < best) {
      second = best;
      best = distance;
      index = i;
    } else if (distance < second) {
      second = distance;
    }
  }
  // Within max_distance, and no worse than ratio x the second best (when there is one).
  bool accept(int max_distance, double ratio) const {
    return index >= 0 && best <= max_distance && (second == INT_MAX || best <= ratio * second);
  }
};

}  // namespace ply_slam
