#pragma once

#include "ply_slam/common/chi_square.h"
#include "ply_slam/common/enum_words.h"

namespace ply_slam {

// How the line term is weighted against the point term in pose optimisation: F(n) of
// PAPER.md §3, with n the number of point observations. kPaper reads the garbled
// "F(n) = 2 n 50" as 2n/50; kOne is 1. Config words: "paper", "one".
enum class LineBalance { kPaper, kOne };
inline constexpr EnumWord<LineBalance> kLineBalanceWords[] = {{LineBalance::kPaper, "paper"},
                                                              {LineBalance::kOne, "one"}};
inline const char* toString(LineBalance balance) { return wordOf(kLineBalanceWords, balance); }

// Which 2D line detector finds the segments. kAuto: LSD where OpenCV has it, else EDLines
// (docs/METHOD.md, "Line segment detection across OpenCV versions"). Config words: "auto", "lsd",
// "edlines".
enum class LineDetectorChoice { kAuto, kLsd, kEdlines };
inline constexpr EnumWord<LineDetectorChoice> kLineDetectorWords[] = {
    {LineDetectorChoice::kAuto, "auto"},
    {LineDetectorChoice::kLsd, "lsd"},
    {LineDetectorChoice::kEdlines, "edlines"}};

// Line features (the config's `lines:` section): LSD segments, merging, LBD, 3D fitting
// (PAPER.md §3.1) and matching between frames.
struct LineOptions {
  bool enabled = false;  // lines in tracking (place recognition always has them)
  LineBalance balance = LineBalance::kPaper;  // F(n) of the line term
  double residual_sigma_px = 1.0;  // B = sigma^2 I of the line residual in pose optimisation
  LineDetectorChoice detector = LineDetectorChoice::kAuto;
  double lsd_scale = 0.35;         // LSD's Gaussian sub-sampling of the image (1 = full size)
  bool refine_edges = true;        // segments moved onto the full-resolution edge (EdgeRefiner)
  double merge_angle_deg = 3.0;    // pieces of one edge: directions within this angle,
  double merge_distance_px = 2.0;  // endpoints this close to the other piece's line,
  double merge_gap_px = 20.0;      // and at most this gap between them
  double min_length_px = 25.0;     // shorter segments (after merging) are dropped
  int max_lines = 150;             // the longest are kept; 0 = all
  double lbd_scale = 0.5;          // image scale the LBD descriptors are computed at (1 = full)
  int lbd_band_width = 5;          // px per band of the LBD descriptor (9 bands), at lbd_scale
  int depth_search_px = 3;         // px across the line searched where a sample has no depth
  double sigma_px = 1.0;           // image noise of a sample (Lambda's image terms, px)
  // Mahalanobis^2 of a sample to the RANSAC line: inlier below (2-DoF 95 %: the distance
  // across the line in the image and in depth).
  double chi2_inlier = kChiSquare95TwoDof;
  int ransac_iterations = 40;        // two-point hypotheses per segment
  int refit_rounds = 2;              // inliers re-selected with the PCA line (0 = the paper's fit)
  int surface_band_px = 5;           // px; depth re-read from the surfaces beside a line (0 = off)
  double min_inlier_ratio = 0.25;    // Th1: inliers / samples along the segment
  double min_length_m = 0.03;        // Th2: shortest accepted 3D segment (m)
  int max_descriptor_distance = 80;  // LBD Hamming distance (of 256 bits): match below
  double match_ratio = 0.9;          // best / second-best distance
  double match_angle_deg = 10.0;     // gate: projected line vs observed line direction
  double match_distance_px = 15.0;   // gate: projected endpoints to the observed line
};

}  // namespace ply_slam
