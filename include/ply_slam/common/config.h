#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include "ply_slam/common/pinhole_camera.h"
#include "ply_slam/dense/occupancy_grid_options.h"
#include "ply_slam/loop/loop_options.h"
#include "ply_slam/mapping/culling_options.h"
#include "ply_slam/mapping/loop_correction_options.h"

namespace ply_slam {

// A config file that cannot be used: names the file, the key and the fault.
class ConfigError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// ORB extraction (features module).
struct OrbParams {
  int num_features = 1000;  // target over all pyramid levels
  int num_levels = 8;
  double scale_factor = 1.2;
  int fast_threshold = 20;     // FAST threshold tried first in every grid cell
  int min_fast_threshold = 7;  // retried in cells where the first one found nothing
  int grid_cell_size = 32;     // px; corners are spread by cell, then by quadtree
  int edge_threshold = 19;     // px kept free at the border (descriptor patch)
};

// Line features (features module): LSD segments, merging, LBD, 3D fitting (PAPER.md §3.1) and
// matching between frames.
struct LineParams {
  bool enabled = false;              // lines in tracking (place recognition always has them)
  std::string balance = "paper";     // F(n) of the line term: "paper" 2n/50, "one" F = 1
  double residual_sigma_px = 1.0;    // B = sigma^2 I of the line residual in pose optimisation
  std::string detector = "auto";     // "lsd", "edlines", or "auto": LSD where OpenCV has it
  double lsd_scale = 0.35;           // LSD's Gaussian sub-sampling of the image (1 = full size)
  bool refine_edges = true;          // segments moved onto the full-resolution edge (EdgeRefiner)
  double merge_angle_deg = 3.0;      // pieces of one edge: directions within this angle,
  double merge_distance_px = 2.0;    // endpoints this close to the other piece's line,
  double merge_gap_px = 20.0;        // and at most this gap between them
  double min_length_px = 25.0;       // shorter segments (after merging) are dropped
  int max_lines = 150;               // the longest are kept; 0 = all
  double lbd_scale = 0.5;            // image scale the LBD descriptors are computed at (1 = full)
  int lbd_band_width = 5;            // px per band of the LBD descriptor (9 bands), at lbd_scale
  int depth_search_px = 3;           // px across the line searched where a sample has no depth
  double sigma_px = 1.0;             // image noise of a sample (Lambda's image terms, px)
  double chi2_inlier = 5.991;        // Mahalanobis^2 of a sample to the RANSAC line: inlier below
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

// Tracking (tracking module).
struct TrackingParams {
  int search_radius_px = 15;            // projection matching window at scale level 0
  int max_descriptor_distance = 60;     // Hamming, accept a match below this
  double nn_ratio = 0.9;                // best / second best distance
  int min_tracked_points = 15;          // fewer inliers: tracking is lost
  int local_map_keyframes = 10;         // covisible keyframes whose points form the local map
  double chi2_outlier = 5.991;          // 2-DoF chi-square 95 %: outlier above
  int optimisation_rounds = 4;          // outlier re-classification rounds
  double keyframe_min_ratio = 0.7;      // new keyframe when tracked < ratio * reference keyframe's
  int keyframe_max_frames = 5;          // or after this many frames
  double keyframe_translation = 0.10;   // m, or after moving this far
  double keyframe_rotation_deg = 15.0;  // or after turning this far
  // m; a tracked pose this far from the constant-velocity prediction is a wrong solve (a
  // camera does not move 15 cm beyond its prediction in one frame), not a motion: lost.
  double max_prediction_error = 0.15;
  int pnp_iterations = 200;  // RANSAC iterations when projection matching fails
  double pnp_reprojection_px = 4.0;
  double max_point_depth = 6.0;  // m; points beyond are not mapped (depth noise grows as Z^2)
};

// YOLOv8-seg instance segmentation (semantic module).
struct YoloParams {
  std::string model_path;        // ONNX export with a fixed input size (README); "" = none
  std::string class_names_path;  // one class name per line, in the model's order
  int input_width = 640;         // the export's input size
  int input_height = 640;
  float score_threshold = 0.25f;  // keep detections whose best class score is above
  float nms_threshold = 0.5f;     // IoU above which the weaker box of one class is dropped
  float mask_threshold = 0.5f;    // sigmoid mask probability that counts as inside
};

// The Delaunay topology check (dynamic module, PAPER.md §3.2).
struct DelaunayConsistencyParams {
  double sigma_factor = 3.0;  // an edge is inconsistent when its length changes > k sigma
  double min_change = 0.01;   // m; and by at least this much (unmodelled errors)
  double pixel_sigma = 1.0;   // px; image noise of a feature, beside the depth noise
  // Features joined by consistent edges form rigid bodies; the largest (the static scene)
  // fixes the camera's motion. Only when it has fewer than 3 features to fit that motion by:
  // those of a body smaller than this share of the largest get weight 1.
  double minority_share = 0.5;
  // m; the predicted camera motion carries a static feature within this of where it is (the
  // constant-velocity prediction errs by ~1 cm over the baseline; a walker moves 5-15 cm).
  double prediction_tolerance = 0.03;
};

// Label dynamic degree and the rejection rules (PAPER.md §3.2).
struct DynamicFilterParams {
  DelaunayConsistencyParams consistency;
  double weight_threshold = 0.5;  // w_th: a feature with a larger dynamic weight is in DP
  double active_degree = 0.2;     // Th_min: r_d above which an active-class instance is dynamic
  double passive_degree = 0.5;    // Th_max: the stricter bound for passive classes
  int min_judged_features = 5;    // an active instance with fewer matched features is dynamic
};

// Dynamic-feature rejection (dynamic module).
struct DynamicParams {
  // off: use every feature; geometric: the Delaunay check, per feature and per depth surface;
  // semantic: drop instances of active classes whole, no geometry; full: the paper's fusion
  // of both (without a segmenter: geometric, modeWithoutSegmenter).
  std::string mode = "full";
  DynamicFilterParams filter;
  int mask_dilation_px = 5;  // dynamic masks miss the blurred rim of a moving object
  // Frames back to the frame the Delaunay check compares with: a person walking at 1 m/s moves
  // 3 cm between two 30 Hz frames, within the depth noise at 3 m; over 0.1 s it moves 10 cm.
  int baseline_frames = 3;
  // A dynamic instance the segmenter misses is carried on (by its flow) for this many frames.
  int carry_frames = 5;
  double match_radius_px = 30.0;  // previous -> current feature search around the prediction
  int max_descriptor_distance = 50;
  std::vector<std::string> active_classes = {
      "person", "bicycle", "car",   "motorcycle", "bus", "train",    "truck", "boat",  "bird",
      "cat",    "dog",     "horse", "sheep",      "cow", "elephant", "bear",  "zebra", "giraffe"};
  std::vector<std::string> passive_classes = {"chair",      "backpack",    "handbag",   "suitcase",
                                              "umbrella",   "bottle",      "cup",       "book",
                                              "cell phone", "sports ball", "teddy bear"};
};

// Dense and semantic octree maps (dense module): keyframe point clouds without the
// pixels of moving things, and an OctoMap ColorOcTree coloured by class.
struct DenseParams {
  bool enabled = true;              // false: no dense map, no octree
  int stride = 2;                   // px between sampled pixels, in both directions
  double min_depth = 0.3;           // m; pixels nearer or farther are left out
  double max_depth = 4.0;           // m; depth noise grows as Z^2
  double voxel_size = 0.02;         // m; voxel filter of keyframe clouds and the global cloud
  int dilation_px = 0;              // extra dilation of the keyframe's dynamic mask
  double octree_resolution = 0.05;  // m; leaf size of the semantic octree
  // OctoMap probability from which a voxel counts as occupied. A hit adds 0.85 log-odds, a
  // ray through takes 0.41: 0.5 = one hit; 0.88 = at least three hits more than... (see yaml)
  double octree_occupancy = 0.88;
  // m; a ray frees the voxels it passes only up to this short of its hit, whose place is
  // uncertain by the depth noise and the keyframe's pose (see yaml)
  double ray_margin = 0.1;
  bool octree_filter = true;          // the dense cloud keeps only points in occupied octree voxels
  std::string colour_mode = "class";  // octree voxel colour: "class" (palette) or "rgb"
  std::string palette;  // file of "class r g b" lines overriding the built-in palette; "" = none
};

struct SystemConfig {
  std::string source_path;  // the file it was loaded from
  PinholeCamera camera;
  OrbParams orb;
  LineParams lines;
  TrackingParams tracking;
  YoloParams segmentation;
  DynamicParams dynamic;
  DenseParams dense;
  OccupancyGridOptions grid;  // 2D occupancy grid from the octree (dense module)
  LoopOptions loop;           // place recognition (loop module); its depth noise is the camera's
  LoopCorrectionOptions loop_correction;  // closing an accepted loop (mapping module)
  CullingOptions culling;                 // retiring keyframes and points (mapping module)
};

// Loads a YAML config. Unknown keys, missing required keys (camera intrinsics, size) and
// out-of-range values throw ConfigError naming the file and key.
SystemConfig loadConfig(const std::string& path);
// The same from YAML text (the ROS nodes rebuild it from the parameter server); errors name
// `source_name` where loadConfig names the file.
SystemConfig loadConfigFromString(const std::string& yaml_text, const std::string& source_name);

}  // namespace ply_slam
