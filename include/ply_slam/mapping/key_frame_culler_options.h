#pragma once

namespace ply_slam {

// When a keyframe says nothing its neighbours do not (ORB-SLAM's KeyFrameCulling).
struct KeyFrameCullerOptions {
  // ORB-SLAM: a keyframe goes when more than 90 % of its landmarks are redundant.
  double redundancy = 0.9;
  // ORB-SLAM (thObs): a landmark is redundant when this many other keyframes see it.
  int min_observers = 3;
  // ORB-SLAM: the other keyframe must see it at the same scale or finer, one level of slack
  // (its level <= this keyframe's level + 1): a coarser view does not replace a finer one.
  int level_slack = 1;
  // ORB-SLAM2 (MapPoint::EraseObservation: bad at <= 2 observations, an RGB-D view counting
  // two): a point left with one keyframe by the erasure is dropped.
  int min_point_observers = 2;
};

}  // namespace ply_slam
