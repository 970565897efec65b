#pragma once

namespace ply_slam {

// When a point landmark is retired (ORB-SLAM's MapPointCulling, with this project's guard).
struct MapPointCullerOptions {
  // ORB-SLAM: a point matched in fewer than a quarter of the frames it was in view of is
  // unreliable (a reflection, a moving object, a bad descriptor).
  double min_found_ratio = 0.25;
  // Ours (the tracker's rule before): a ratio over fewer views says little.
  int min_visible = 10;
  // ORB-SLAM: a new point is judged by its observers from this many keyframes after its own on.
  int probation_keyframes = 2;
  // ORB-SLAM2 retires a point seen by <= 2 (monocular) or <= 3 (stereo, RGB-D) observations
  // then, but counts an RGB-D view twice: both mean "fewer than two keyframes".
  int min_keyframe_observers = 2;
};

}  // namespace ply_slam
