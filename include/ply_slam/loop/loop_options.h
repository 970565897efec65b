#pragma once

#include <string>
#include <vector>

#include "ply_slam/common/pinhole_camera.h"

namespace ply_slam {

// Every threshold of loop detection (PAPER.md §3.3). Values the paper states are marked
// "paper"; the others are our choices (the paper gives none) and say why.
struct LoopOptions {
  // --- Place recognition as a whole ------------------------------------------------------
  // false: the SLAM system runs no loop detection (tools such as ply_slam_loops still can).
  bool enabled = false;
  // Vocabulary files (ply_slam_vocabulary). "" = the default that scripts/setup.sh trains,
  // build/vocabulary/{orb,lbd}_k10_l5.voc; a relative path is taken from the package source
  // folder (vocabularyPath()).
  std::string orb_vocabulary;
  std::string lbd_vocabulary;

  // --- Instance similarity ---------------------------------------------------------------
  // paper: S_inst = w_pos S_pos + w_iou S_IoU.
  double position_weight = 0.6;
  double iou_weight = 0.4;
  // paper: eps in S_IoU = inter / (union + eps), keeps empty boxes finite.
  double iou_epsilon = 1e-6;
  // Th_aver: neighbourhood similarity S_aver above it boosts, below it penalises S_inst.
  // Ours: S_aver = 1 - mean |a_k - b_k| of diag-normalised distances, so 0.9 means "the
  // same-class neighbours lie on average within 10 % of the image diagonal of where they were".
  double spatial_consistency_threshold = 0.9;
  double consistency_boost = 0.1;    // paper: S_inst = min(1, S_inst + 0.1) when consistent
  double consistency_penalty = 0.8;  // paper: S_inst = 0.8 S_inst when inconsistent
  // paper: step 1, pairs with S_pos above this are a sure match (credited 1).
  double sure_position = 0.95;
  // paper: Th_dyna = max(dyna_floor, min(dyna_ceiling, dyna_ceiling - dyna_step min(n1, n2))).
  double dyna_ceiling = 0.6;
  double dyna_floor = 0.3;
  double dyna_step = 0.05;
  // Potentially moving COCO classes, dropped before matching (their position says nothing
  // about the place). Same list as config/tum_fr1.yaml dynamic.active_classes.
  std::vector<std::string> dynamic_classes = {
      "person", "bicycle", "car",   "motorcycle", "bus", "train",    "truck", "boat",  "bird",
      "cat",    "dog",     "horse", "sheep",      "cow", "elephant", "bear",  "zebra", "giraffe"};

  // --- Score fusion ----------------------------------------------------------------------
  double point_line_weight = 0.6;  // paper: S_fin = 0.6 S_pl + 0.4 S_inst_fin
  double instance_weight = 0.4;

  // --- Candidate selection ---------------------------------------------------------------
  // Keyframes sharing at least this many landmarks are covisible: never loop candidates of
  // each other, and the query's best of them is its reference. ORB-SLAM's 15: in a small room
  // every keyframe shares a few points with every other, which says little.
  int min_covisible_shared = 15;
  // Candidates must be more than this much older than the query (s). A return to a place after a
  // while is a loop; a keyframe of the last seconds that tracking failed to connect is the
  // local map's and relocalisation's business, and closing a "loop" to it corrects no drift.
  // ply_slam_loops defines true loops as more than 10 s apart (--min-gap-s), by the same
  // comparison of the two stamps' difference (30 Hz frames 10 s apart are common).
  double min_candidate_age_s = 10.0;
  // alpha: minimum normalised score S_fin(query, cand) / S_fin(query, best covisible). The
  // paper sweeps 0.1..0.8; 0.3 is DBoW2's usual normalised-score threshold.
  double min_normalised_score = 0.3;
  // A candidate is accepted once its group was consistent over this many consecutive queries
  // (PAPER.md gives no rule; 3 is what DBoW2 and ORB-SLAM use). The first query counts as 1.
  int consistency = 3;

  // --- Geometric check -------------------------------------------------------------------
  // Matches come through the direct index: only descriptors under one vocabulary node this
  // many levels above the words are compared. With k 10, L 5: 3 up = level 2, 100 nodes, as
  // ORB-SLAM compares at its vocabulary's level 2 (of 6) too.
  int direct_index_levels_up = 3;
  int match_max_distance = 50;        // Hamming (of 256 bits), ORB-SLAM's TH_LOW
  double match_ratio = 0.75;          // best / second best, ORB-SLAM's loop-search ratio
  int ransac_iterations = 200;        // 3-point hypotheses; 40 % inliers need ~70 for 99.9 %
  unsigned ransac_seed = 42;          // fixed: the same input gives the same answer
  int refine_iterations = 5;          // re-fit on the inliers until the set stops changing
  double inlier_sigma_factor = 3.0;   // 3D inlier: |P_q - T P_c| < k sqrt(var(Z_q) + var(Z_c))
  double min_inlier_distance = 0.01;  // m; floor of that bound (pixel noise, calibration)
  DepthNoiseModel depth_noise;        // sigma_Z^2 = alpha Z^2 + beta Z + gamma
  int min_inliers_3d = 15;            // at least this many 3D inliers (ORB-SLAM2 asks ~20)
  double reprojection_px = 4.0;       // px, in both images
  int min_reprojection_inliers = 15;  // at least this many matches reproject in both images
  // A loop is a return to a place: the check's own estimate of the motion between the two
  // cameras (drift does not enter it) must be at most this far and this much turned. Views of
  // the same scene from farther away (down a corridor both see its end; the same wall a step
  // back) are left to tracking's local map. Below ply_slam_loops' true-loop bound (0.3 m,
  // 20 deg) by the check's largest motion error on the synthetic loop scenes (0.07 m, 0.9 deg)
  // and a margin for real depth.
  double max_revisit_distance_m = 0.2;
  double max_revisit_angle_deg = 15.0;
};

}  // namespace ply_slam
