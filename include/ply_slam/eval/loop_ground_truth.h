#pragma once

#include <Eigen/Geometry>
#include <opencv2/core.hpp>
#include <vector>

#include "ply_slam/common/pinhole_camera.h"

namespace ply_slam {

// When two keyframes are a true loop for ply_slam_loops: taken more than min_gap_s apart, their
// ground-truth camera centres within max_distance_m and their orientations within
// max_angle_deg, and their views overlap: at least min_overlap of one keyframe's sampled depth
// points (every pixel_step-th pixel in both directions, valid depth) land inside the other's
// image, in front of it, where the other's depth agrees within max(depth_tolerance_m,
// depth_tolerance_ratio z) (so points hidden behind a wall or out of view do not count).
// A place is its static scene: pixels on moving things (people) in either view take no part,
// neither as a's points nor where they land on b (what a person hides in b is not known to be
// seen or not).
struct LoopGroundTruthParams {
  double min_gap_s = 10.0;
  double max_distance_m = 0.3;
  double max_angle_deg = 20.0;
  double min_overlap = 0.3;
  int pixel_step = 4;  // of the (already downsampled) depth images
  double depth_tolerance_m = 0.05;
  double depth_tolerance_ratio = 0.05;
  // A pair is a false loop beyond these (or without overlapping views, or too soon); between
  // them and max_distance_m / max_angle_deg, with overlapping views, it counts neither way:
  // there score and distance are uncorrelated (issue #16), views a step apart cannot be told
  // from one place. The "soft" ground truth of place-recognition benchmarks (NetVLAD's
  // positives within 10 m, negatives beyond 25 m), at room scale.
  double false_distance_m = 0.6;
  double false_angle_deg = 40.0;
};

// What the ground truth says of a pair of keyframes.
enum class LoopTruth { kTrue, kDontCare, kFalse };

// A keyframe as the ground truth sees it.
struct GroundTruthView {
  long id = 0;
  double stamp = 0.0;
  Eigen::Isometry3d T_wc = Eigen::Isometry3d::Identity();  // ground truth
  cv::Mat depth;   // 32FC1 m, 0 = none; any size: `camera` must describe it
  cv::Mat movers;  // 8UC1 of depth's size, non-zero on moving things; empty = none
};

// The share of a's sampled valid depth points off the movers, landing off b's movers, that b
// sees at the same depth (0 when a has none).
double viewOverlap(const GroundTruthView& a, const GroundTruthView& b, const PinholeCamera& camera,
                   const LoopGroundTruthParams& params);

// kTrue: time, distance and angle pass, and the larger of the two overlaps reaches
// min_overlap; kDontCare: the views overlap so, but distance or angle lie between the true and
// the false bounds; kFalse: everything else.
LoopTruth loopTruth(const GroundTruthView& a, const GroundTruthView& b, const PinholeCamera& camera,
                    const LoopGroundTruthParams& params);

}  // namespace ply_slam
