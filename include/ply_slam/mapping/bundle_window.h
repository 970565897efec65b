#pragma once

#include <array>
#include <memory>
#include <vector>

#include "ply_slam/common/point_residual.h"
#include "ply_slam/common/se3_params.h"
#include "ply_slam/map/key_frame.h"

namespace ply_slam {

// A bundle adjustment taken out of the map: the poses and landmark positions as numbers the
// solver changes, and the observations that tie them. Solving it reads nothing of the map, so
// the map's lock is free meanwhile (LocalBundleAdjuster: gather, solve, apply).
struct BundleWindow {
  struct Pose {
    // Alive until applied: a local window is applied before the mapping side erases anything; a
    // global one holds its keyframes in `keyframes`.
    KeyFrame* keyframe = nullptr;
    Se3Params params;    // T_cw
    bool local = false;  // in the window: its pose is written back
    bool fixed = false;  // outside the window, or the first keyframe (the gauge)
  };
  struct Observation {
    size_t pose = 0;   // into poses
    size_t point = 0;  // into points
    size_t index = 0;  // the keypoint of the pose's keyframe
    PointResidual residual;
    bool behind = false;  // behind the keyframe when gathered: no constraint, an outlier
  };
  std::vector<Pose> poses;
  std::vector<std::shared_ptr<KeyFrame>> keyframes;  // gatherAll's: culled meanwhile, still here
  std::vector<std::shared_ptr<MapPoint>> landmarks;
  std::vector<std::array<double, 3>> points;  // positions, as landmarks
  std::vector<Observation> observations;
  int max_iterations = 0;
};

}  // namespace ply_slam
