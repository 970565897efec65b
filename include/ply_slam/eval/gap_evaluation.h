#pragma once

#include <optional>
#include <string>
#include <vector>

#include "ply_slam/common/stamped_pose.h"
#include "ply_slam/eval/trajectory_metrics.h"

namespace ply_slam {

// Frames from..to-1 of a sequence taken out of a run (0-based): skipped (the camera carried
// elsewhere, a kidnap) or black (the lens covered).
struct FrameGap {
  long from = 0, to = 0;
  bool black = false;
  bool holds(size_t frame) const {
    return static_cast<long>(frame) >= from && static_cast<long>(frame) < to;
  }
};
// "FROM:TO" with 1 <= FROM < TO (a frame before the gap to be lost from), or nothing.
std::optional<FrameGap> parseFrameGap(const std::string& text, bool black);

// A relocalisation farther than this from the truth is wrong: well beyond the ATE of every
// sequence tracked without a gap (<= 0.03 m), within what a camera moved between two places.
struct GapTolerance {
  double metres = 0.1;
  double degrees = 5.0;
};

// How a run came through a gap in its frames (frames skipped: the camera carried elsewhere;
// or black: the lens covered). Poses are judged in the frame the poses before the gap are
// aligned in: a relocalisation must put the camera back into the map it had.
struct GapReport {
  bool relocalised = false;    // some pose after the gap
  double first_error_m = 0.0;  // of the first pose after the gap
  double first_error_deg = 0.0;
  ErrorStats after;                // ATE over the poses after the gap, m
  long relocalisations = 0;        // of the stamps given, those with a ground-truth pose
  long wrong_relocalisations = 0;  // of them, beyond the tolerance
};

// est: the run's trajectory; gap_start / gap_end: the stamps of the last frame before the gap
// and the first frame after it; relocalised: stamps of the frames tracking relocalised in
// (anywhere in the run). Throws std::runtime_error when fewer than 3 poses before the gap
// associate with the ground truth (no frame to judge in).
GapReport evaluateGap(const Trajectory& gt, const Trajectory& est, double gap_start, double gap_end,
                      const std::vector<double>& relocalised, const GapTolerance& tolerance = {});

}  // namespace ply_slam
