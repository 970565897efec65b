#pragma once

#include <Eigen/Core>
#include <vector>

namespace ply_slam {

// A 2D point with a weight (how much it counts in a line fit).
struct WeightedPoint2 {
  Eigen::Vector2d p;
  double weight = 1.0;
};

// Weighted total-least-squares line through the points: the weighted centroid and the unit
// principal axis of the weighted scatter. False when the weights sum to zero or the points
// have no spread (the direction is then arbitrary).
bool fitWeightedLine(const std::vector<WeightedPoint2>& points, Eigen::Vector2d& centroid,
                     Eigen::Vector2d& direction);

}  // namespace ply_slam
