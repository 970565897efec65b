// Offline run of ply_slam on a TUM RGB-D folder (options: kUsage below).
// Writes CameraTrajectory.txt, KeyFrameTrajectory.txt, timing.csv, summary.json and
// trajectory.png into DIR, and with dense.enabled the dense maps (dense_map.pcd/.ply,
// semantic_octree.ot, octree.bt, map_legend.txt, map_top.png) and, with grid.enabled, the
// occupancy grid (map.pgm + map.yaml for map_server, grid.png).
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iomanip>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>

#include "ply_slam/common/command_line.h"
#include "ply_slam/common/statistics.h"
#include "ply_slam/common/stopwatch.h"
#include "ply_slam/dense/dense_mapping_worker.h"
#include "ply_slam/dense/grid_map_files.h"
#include "ply_slam/dense/grid_renderer.h"
#include "ply_slam/dense/map_export.h"
#include "ply_slam/dense/occupancy_grid_builder.h"
#include "ply_slam/dense/top_view_renderer.h"
#include "ply_slam/eval/feature_classification.h"
#include "ply_slam/eval/gap_evaluation.h"
#include "ply_slam/eval/trajectory_metrics.h"
#include "ply_slam/eval/trajectory_plot.h"
#include "ply_slam/io/atomic_file.h"
#include "ply_slam/io/earlier_outputs.h"
#include "ply_slam/io/file_writes.h"
#include "ply_slam/io/image_file.h"
#include "ply_slam/io/run_arguments.h"
#include "ply_slam/io/tum_sequence.h"
#include "ply_slam/io/tum_trajectory_file.h"
#include "ply_slam/semantic/lagged_segmenter.h"
#include "ply_slam/semantic/live_segmenter.h"
#include "ply_slam/semantic/mask_folder_segmenter.h"
#include "ply_slam/semantic/segmenter_choice.h"
#include "ply_slam/system/system.h"
#include "ply_slam/system/system_config.h"
#include "ply_slam/system/tracking_image.h"

namespace fs = std::filesystem;
using namespace ply_slam;
using Json = nlohmann::ordered_json;

namespace {

struct Options : RunArguments {
  long max_frames = -1;
  SegmenterChoice segmentation;
  bool no_lines = false;           // overrides lines.enabled of the config
  bool no_loop = false;            // overrides loop.enabled of the config
  std::string dynamic;             // overrides dynamic.mode of the config
  bool live = false;               // frames at their own pace, segmentation beside
  bool realtime = false;           // the mapping side on a thread of its own
  long segment_lag = 0;            // > 0: LaggedSegmenter, live's masks reproducibly
  long save_images = 0;            // every N frames a tracking image; 0 = none
  std::string ground_truth_masks;  // walker masks: feature classification, ghost count
  std::string save_map;            // folder the map is saved into at the end; "" = none
  std::string map;                 // folder of a saved map to localise in; "" = a new map
  bool localisation_only = true;   // with --map: add no keyframes
  bool localisation_only_given = false;
  std::optional<FrameGap> gap;  // --kidnap / --cover: frames taken out of the run
};

const char* const kUsage =
    "usage: ply_slam_tum --sequence DIR --config FILE --out DIR"
    " [--segmenter none|masks|yolo] [--model ONNX --input WxH]"
    " [--dynamic off|geometric|semantic|full] [--live] [--realtime] [--segment-lag N]"
    " [--save-images N]"
    " [--max-frames N]"
    " [--no-lines] [--no-loop] [--ground-truth-masks DIR] [--save-map DIR]"
    " [--map DIR [--localisation-only true|false]] [--kidnap FROM:TO | --cover FROM:TO]\n"
    "  --no-lines: points only, whatever lines.enabled says\n"
    "  --no-loop: no place recognition nor loop closure, whatever loop.enabled says\n"
    "  --dynamic: how dynamic features are rejected (default: the config's dynamic.mode)\n"
    "  --live: play the frames at their recorded rate and segment on a second thread, as\n"
    "          the ROS node does (results then depend on timing)\n"
    "  --realtime: the mapping side (local BA, culling, loop closure) on a thread of its own\n"
    "          beside tracking, as tracking_node runs it with mapping_apart:=false (results\n"
    "          then depend on timing); without it the tracker waits for the mapping side at\n"
    "          each keyframe and runs repeat bit for bit\n"
    "  --save-images N: write every N-th tracking image to DIR/images\n"
    "  --segment-lag N: segment every N-th frame, its masks used from N frames later and\n"
    "          carried to each frame, as --live's are, but reproducibly\n"
    "  --segmenter masks: instance masks from DIR/masks and DIR/instances.txt\n"
    "  --segmenter yolo: YOLOv8-seg, model from the config's segmentation section or"
    " --model/--input (only with --segmenter yolo)\n"
    "  --ground-truth-masks DIR: count dense points and octree voxels from the people of\n"
    "    DIR/masks (default: the sequence's own masks/ when it has them)\n"
    "  --save-map DIR: write the map at the end into DIR/map.plymap (a map --map loads)\n"
    "  --map DIR: start in the map saved in DIR: relocalise in it, then track against it;\n"
    "    poses are in its frame, frames before the relocalisation are lost\n"
    "  --localisation-only true|false: with --map, add no keyframes (default true) or extend\n"
    "    the map\n"
    "  --kidnap FROM:TO: frames FROM..TO-1 (0-based) are skipped: the camera jumps; --cover:\n"
    "    they are black (rgb and depth). summary.json's gap says how it relocalised\n"
    "Exit codes: 0 ok; 1 a frame or an output could not be read or written (what could be\n"
    "written is); 2 usage error; 3 every output written but the ground truth could not be\n"
    "evaluated (summary.json evaluation_error says why).\n";

constexpr int kExitEvaluationFailed = 3;

long parseCount(const std::string& option, const std::string& text) {
  return wholeNumberArgument(option, text, 0, 1000000000L, "a whole number >= 0");
}

void setOption(Options& o, const std::string& arg, const std::string& value) {
  if (o.segmentation.take(arg, value) || o.take(arg, value)) return;
  if (arg == "--ground-truth-masks") {
    o.ground_truth_masks = value;
  } else if (arg == "--max-frames") {
    o.max_frames = wholeNumberArgument(arg, value, 1, 1000000000L, "a whole number >= 1");
  } else if (arg == "--dynamic") {
    o.dynamic = value;
  } else if (arg == "--segment-lag") {
    o.segment_lag = wholeNumberArgument(arg, value, 1, 1000, "a whole number of frames >= 1");
  } else if (arg == "--save-images") {
    o.save_images = parseCount(arg, value);
  } else if (arg == "--save-map") {
    o.save_map = value;
  } else if (arg == "--map") {
    o.map = value;
  } else if (arg == "--localisation-only") {
    if (value != "true" && value != "false")
      throw UsageError("--localisation-only takes true or false, got '" + value + "'");
    o.localisation_only = value == "true";
    o.localisation_only_given = true;
  } else if (arg == "--kidnap" || arg == "--cover") {
    if (o.gap) throw UsageError("--kidnap and --cover: one gap per run");
    o.gap = parseFrameGap(value, arg == "--cover");
    if (!o.gap)
      throw UsageError(arg + " takes FROM:TO, frame numbers with 1 <= FROM < TO, got '" + value +
                       "'");
  }
}

void checkOptions(const Options& o) {
  o.segmentation.check();
  if (!o.dynamic.empty()) try {
      parseDynamicMode(o.dynamic);
    } catch (const std::invalid_argument&) {
      throw UsageError("unknown dynamic mode '" + o.dynamic +
                       "' (off, geometric, semantic or full)");
    }
  if (o.live && o.segmentation.kind == "none") throw UsageError("--live needs a segmenter");
  if (o.segment_lag > 0 && (o.live || o.segmentation.kind == "none"))
    throw UsageError("--segment-lag needs a segmenter and not --live (which lags by itself)");
  if (o.localisation_only_given && o.map.empty())
    throw UsageError("--localisation-only needs --map");
  o.require();
}

Options parse(int argc, char** argv) {
  Options o;
  CommandLine line;
  line.usage_text = kUsage;
  line.flags = {"--no-lines", "--live", "--realtime", "--no-loop"};
  line.options = {"--sequence",    "--config",
                  "--out",         "--segmenter",
                  "--model",       "--input",
                  "--dynamic",     "--ground-truth-masks",
                  "--segment-lag", "--max-frames",
                  "--save-images", "--save-map",
                  "--map",         "--localisation-only",
                  "--kidnap",      "--cover"};
  line.on_flag = [&](const std::string& flag) {
    (flag == "--live"       ? o.live
     : flag == "--realtime" ? o.realtime
     : flag == "--no-loop"  ? o.no_loop
                            : o.no_lines) = true;
  };
  line.on_option = [&](const std::string& arg, const std::string& value) {
    setOption(o, arg, value);
  };
  try {
    line.parse(argc, argv);
    checkOptions(o);
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
  return o;
}

double peakRssMb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss / 1024.0;  // ru_maxrss is in KiB on Linux
}

// Resident memory now (MB), from /proc/self/statm; 0 where that does not exist.
double currentRssMb() {
  std::ifstream statm("/proc/self/statm");
  long pages = 0, resident = 0;
  if (!(statm >> pages >> resident)) return 0.0;
  return resident * (sysconf(_SC_PAGESIZE) / 1024.0) / 1024.0;
}

// summary.json gives 6 significant digits, as it always has.
double rounded(double value) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.6g", value);
  return std::strtod(text, nullptr);
}

Json statsJson(const ErrorStats& s) {
  return {{"pairs", s.count},
          {"rmse", rounded(s.rmse)},
          {"mean", rounded(s.mean)},
          {"median", rounded(s.median)},
          {"max", rounded(s.max)}};
}

// Dense and semantic octree maps ------------------------------------------------------------------

// The ground-truth masks of the moving things (active classes) in one frame, undilated: what
// a ghost in the maps would come from.
cv::Mat walkerPixels(const std::vector<Instance>& ground_truth, const cv::Size& size,
                     const DynamicOptions& dynamic) {
  cv::Mat walkers = cv::Mat::zeros(size, CV_8UC1);
  for (const auto& instance : ground_truth)
    if (std::count(dynamic.active_classes.begin(), dynamic.active_classes.end(),
                   instance.class_name))
      walkers |= instance.mask;
  return walkers;
}

std::unique_ptr<MaskFolderSegmenter> groundTruthMasks(const Options& options,
                                                      const TumSequence& sequence) {
  std::string folder = options.ground_truth_masks;
  if (folder.empty() && fs::exists(fs::path(sequence.folder()) / "masks") &&
      fs::exists(fs::path(sequence.folder()) / "instances.txt"))
    folder = sequence.folder();
  return folder.empty() ? nullptr : std::make_unique<MaskFolderSegmenter>(folder);
}

Json walkersJson(DenseMap& map, size_t points, const std::vector<SemanticOctree::Voxel>& voxels) {
  size_t walker_majority = 0, walker_any = 0;
  for (const auto& v : voxels) {
    walker_majority += 2 * v.tagged > v.hits;
    walker_any += v.tagged > 0;
  }
  const long walker_points = map.taggedPoints();
  const long unfiltered = map.taggedPoints(true);
  const auto share = [](double part, double whole) { return rounded(whole ? part / whole : 0.0); };
  return {{"points", walker_points},
          {"points_share", share(walker_points, points)},
          {"points_before_octree_filter", unfiltered},
          {"points_before_octree_filter_share",
           rounded(double(unfiltered) / std::max<size_t>(1, map.numUnfilteredPoints()))},
          {"voxels_majority", walker_majority},
          {"voxels_majority_share", share(walker_majority, voxels.size())},
          {"voxels_any", walker_any},
          {"voxels_any_share", share(walker_any, voxels.size())}};
}

// An empty cloud is no PCD or PLY file (PCL writes none): said, not left for the user to find.
void reportLeftOutClouds(DenseMap& map, Json& dense) {
  if (map.numGlobalPoints() > 0) return;
  const std::string why =
      "the dense cloud is empty: " + std::to_string(map.numKeyFrames()) + " keyframes gave " +
      std::to_string(map.numUnfilteredPoints()) +
      " points, none in an octree voxel seen occupied often enough yet (dense.octree_filter, "
      "dense.octree_occupancy)";
  dense["files_left_out"] = {"dense_map.pcd", "dense_map.ply"};
  dense["files_left_out_reason"] = why;
  std::cerr << "ply_slam_tum: dense_map.pcd and dense_map.ply not written: " << why << "\n";
}

// The occupancy grid from the octree: map.pgm, map.yaml (in the floor frame) and grid.png;
// returns the summary's "grid" member.
Json writeGrid(const SemanticOctree& octree, const SystemConfig& config,
               const Trajectory& trajectory, const fs::path& out, const std::string& title,
               FileWrites& outputs) {
  Stopwatch watch;
  const OccupancyGridBuilder builder(
      config.grid, OccupancyGridBuilder::labelsOf(octree.palette(), config.dynamic.active_classes));
  const OccupancyGrid grid = builder.build(octree, trajectory);
  const double ms = watch.elapsedMs();
  outputs.attempt([&] { writeGridMap(out.string(), grid); });
  outputs.attempt([&] {
    GridRenderer().write((out / "grid.png").string(), grid, trajectory,
                         title + "   occupancy grid (" + grid.floor().method + " floor)");
  });
  const Eigen::Vector3d up = grid.floor().T_world_floor.linear().col(2);
  // The first camera's height above the floor found: a check against the rig's height.
  const double camera_height =
      trajectory.empty()
          ? 0.0
          : (grid.floor().T_world_floor.inverse() * trajectory.front().T_wc.translation()).z();
  std::cout << "occupancy grid " << grid.width() << " x " << grid.height() << " cells, "
            << grid.count(OccupancyGrid::kOccupied) << " occupied, "
            << grid.count(OccupancyGrid::kFree) << " free (" << grid.floor().method << " floor)\n";
  return {{"width", grid.width()},
          {"height", grid.height()},
          {"resolution", rounded(grid.resolution())},
          {"occupied", grid.count(OccupancyGrid::kOccupied)},
          {"free", grid.count(OccupancyGrid::kFree)},
          {"unknown", grid.count(OccupancyGrid::kUnknown)},
          {"floor", grid.floor().method},
          {"floor_support", grid.floor().support},
          {"up", {rounded(up.x()), rounded(up.y()), rounded(up.z())}},
          {"first_camera_height", rounded(camera_height)},
          {"ms", rounded(ms)}};
}

// Drains the worker, re-places keyframes at their final poses, writes the maps and
// map_top.png; returns the summary.json object.
// `grid`: the occupancy grid's summary member, with grid.enabled.
Json finishDenseMaps(DenseMappingWorker& dense, const System& system, const SystemConfig& config,
                     const Trajectory& trajectory, const fs::path& out, const std::string& title,
                     bool counted_walkers, FileWrites& outputs, Json& grid) {
  MapUpdate final_poses;
  for (const auto& keyframe : system.map().keyFrames())
    if (keyframe) final_poses.keyframes.push_back({keyframe->id, keyframe->T_cw});
  dense.push(final_poses);
  dense.finish();
  const std::vector<double> ms = dense.keyFrameMs();
  Json json;
  dense.withMaps([&](DenseMap& map, const SemanticOctree& octree) {
    Stopwatch global_watch;
    const size_t points = map.numGlobalPoints();
    const double global_ms = global_watch.elapsedMs();
    outputs.attempt([&] { writeDenseMaps(out.string(), map, octree); });
    const std::vector<SemanticOctree::Voxel> voxels = octree.occupiedVoxels();
    outputs.attempt([&] {
      TopViewRenderer().write((out / "map_top.png").string(), voxels, trajectory,
                              TopViewRenderer::upFromTrajectory(trajectory), octree.palette(),
                              title + "   semantic octree, top view");
    });
    json = {{"keyframes", map.numKeyFrames()},
            {"points", points},
            {"points_before_octree_filter", map.numUnfilteredPoints()},
            {"occupied_voxels", voxels.size()},
            {"ms_per_keyframe_median", rounded(median(ms, 0.0))},
            {"ms_per_keyframe_p95", rounded(percentile(ms, 0.95, 0.0))},
            {"global_cloud_ms", rounded(global_ms)},
            {"max_queue", dense.maxQueueLength()},
            {"dropped_unbuilt", dense.droppedUnbuilt()},
            {"rejected_packets", dense.rejectedPackets()},
            {"cloud_bytes", map.memoryBytes()},
            {"octree_bytes", octree.memoryBytes()},
            {"memory_bytes", map.memoryBytes() + octree.memoryBytes()}};
    if (counted_walkers) json["walkers"] = walkersJson(map, points, voxels);
    reportLeftOutClouds(map, json);
    if (config.grid.enabled) grid = writeGrid(octree, config, trajectory, out, title, outputs);
    std::cout << "dense map " << points << " points, octree " << voxels.size()
              << " occupied voxels; dense+octree ms per keyframe median " << median(ms, 0.0)
              << ", p95 " << percentile(ms, 0.95, 0.0) << "\n";
  });
  if (dense.rejectedPackets() > 0)
    std::cerr << "ply_slam_tum: dense maps left out " << dense.rejectedPackets()
              << " keyframes: " << dense.firstError() << "\n";
  return json;
}

// Loop closure's counts and each correction (null when loop closure is off).
Json loopsJson(const System& system,
               const std::vector<std::shared_ptr<const LoopCorrection>>& corrections) {
  const LoopClosureCounts* counts = system.loopCounts();
  if (!counts) return nullptr;
  const GlobalBundleAdjustmentCounts global = system.globalBundleAdjustmentCounts();
  double pose_graph_ms = 0.0, global_ba_ms = 0.0;
  Json each = Json::array();
  for (const auto& c : corrections) {
    pose_graph_ms += c->pose_graph.ms;
    global_ba_ms += c->global_ba_ms;
    each.push_back({{"query", c->loop.query_id},
                    {"candidate", c->loop.candidate_id},
                    {"moved_m", rounded(c->shift.moved_m)},
                    {"turned_deg", rounded(c->shift.turned_deg)},
                    {"connected", c->connected_keyframes},
                    {"fused", c->fused},
                    {"loop_links", c->loop_links},
                    {"pose_graph_iterations", c->pose_graph.iterations},
                    {"pose_graph_ms", rounded(c->pose_graph.ms)},
                    {"global_ba_ms", rounded(c->global_ba_ms)},
                    {"ms", rounded(c->ms)}});
  }
  return {{"queries", counts->queries},
          {"detected", counts->detected},
          {"accepted", counts->accepted},
          {"implausible", counts->implausible},
          {"corrected", counts->corrected},
          {"pose_graph_ms", rounded(pose_graph_ms)},
          {"global_ba_ms", rounded(global_ba_ms)},
          {"global_ba",
           {{"started", global.started},
            {"applied", global.applied},
            {"abandoned", global.abandoned},
            {"solve_ms", rounded(global.solve_ms)}}},
          {"corrections", each}};
}

// What the frames add up to in summary.json.
struct RunCounts {
  std::vector<double> total_ms, lines_ms, segment_ms;
  double line_inliers = 0.0;
  size_t dynamic_features = 0;
  long frames = 0, lost = 0, keyframes_created = 0, keyframes_culled = 0, points_culled = 0;
  long points_merged = 0, observations_fused = 0;  // the mapping side's fusion
  long keyframes_held_back = 0;  // frames that wanted a keyframe while the mapping side was behind
  long first_tracked = -1;       // index of the first tracked frame (in a loaded map: relocalised)

  void add(const FrameResult& r) {
    if (first_tracked < 0 && r.tracking.state == TrackingState::kOk) first_tracked = frames;
    ++frames;
    if (r.tracking.state != TrackingState::kOk) ++lost;
    keyframes_created += r.tracking.new_keyframe != nullptr;
    keyframes_held_back += r.tracking.keyframe_held_back;
    total_ms.push_back(r.timing.total_ms);
    lines_ms.push_back(r.timing.lines_ms);
    line_inliers += r.tracking.line_inliers;
    dynamic_features += r.dynamic_features;
  }
  void add(const MappedKeyFrame& mapped) {
    keyframes_culled += static_cast<long>(mapped.map_update->erased_keyframes.size());
    points_culled += mapped.culled_points;
    points_merged += mapped.merged_points;
    observations_fused += mapped.fused_observations;
  }
};

// Every file a run may write into --out; those of an earlier run are removed at the start.
std::vector<std::string> outputNames(const fs::path& out) {
  std::vector<std::string> names = {"CameraTrajectory.txt",
                                    "KeyFrameTrajectory.txt",
                                    "timing.csv",
                                    "summary.json",
                                    "trajectory.png",
                                    "dense_map.pcd",
                                    "dense_map.ply",
                                    "semantic_octree.ot",
                                    "octree.bt",
                                    "map_legend.txt",
                                    "map_top.png",
                                    "map.pgm",
                                    "map.yaml",
                                    "grid.png"};
  std::error_code error;
  for (const auto& entry : fs::directory_iterator(out / "images", error)) {
    const std::string stem = entry.path().stem().string();  // saveImage's %06ld.jpg
    if (entry.path().extension() == ".jpg" && stem.size() >= 6 &&
        stem.find_first_not_of("0123456789") == std::string::npos)
      names.push_back("images/" + entry.path().filename().string());
  }
  return names;
}

void removeEarlierRun(const fs::path& out) {
  const std::vector<std::string> removed = removeEarlierOutputs(out, outputNames(out));
  if (removed.empty()) return;
  std::cout << "removed " << removed.size() << " output(s) of an earlier run from " << out.string()
            << ":";
  for (const std::string& name : removed) std::cout << ' ' << name;
  std::cout << "\n";
}

const char* const kTimingHeader =
    "frame,stamp,state,method,inliers,line_inliers,keyframe,features_ms,lines_ms,tracking_ms,"
    "mapping_ms,total_ms,rss_mb,keyframes,map_points,map_wait_ms,follow_ms\n";

void writeTimingRow(std::ostream& timing, const FrameResult& r, const System& system) {
  timing << r.frame_id << ',' << std::fixed << std::setprecision(6) << r.stamp << ','
         << toString(r.tracking.state) << ',' << r.tracking.method << ',' << r.tracking.inliers
         << ',' << r.tracking.line_inliers << ',' << (r.tracking.new_keyframe != nullptr) << ','
         << std::setprecision(3) << r.timing.features_ms << ',' << r.timing.lines_ms << ','
         << r.timing.tracking_ms << ',' << r.timing.mapping_ms << ',' << r.timing.total_ms << ','
         << std::setprecision(1) << currentRssMb() << ',' << system.map().numKeyFrames() << ','
         << system.map().numMapPoints() << ',' << std::setprecision(3) << r.timing.map_wait_ms
         << ',' << r.timing.follow_ms << '\n';
}

// ATE and RPE against the sequence's ground truth; a ground truth that does not fit the run
// (no overlap in time, too few tracked frames) is an error message naming the file.
struct Evaluation {
  Json fields = Json::object();
  Trajectory aligned;
  std::string title, error;
};

Evaluation evaluate(const TumSequence& sequence, const Trajectory& trajectory) {
  Evaluation e;
  e.aligned = trajectory;
  e.error = sequence.groundTruthProblem();  // a groundtruth.txt there that gives none
  if (!sequence.hasGroundTruth()) return e;
  const std::string file = (fs::path(sequence.folder()) / "groundtruth.txt").string();
  if (trajectory.size() < 3) {
    e.error = file + ": not evaluated, only " + std::to_string(trajectory.size()) +
              " tracked frames (ATE needs 3)";
    return e;
  }
  try {
    const AteResult ate = computeAte(sequence.groundTruth(), trajectory);
    const RpeResult rpe = computeRpeFrames(sequence.groundTruth(), trajectory, 1);
    const SimilarityAteResult sim = computeAteSimilarity(sequence.groundTruth(), trajectory);
    e.fields["ate"] = statsJson(ate.translation);
    e.fields["ate_sim3"] = {{"scale", rounded(sim.scale)}, {"rmse", rounded(sim.translation.rmse)}};
    e.fields["rpe_translation_per_frame"] = statsJson(rpe.translation);
    e.fields["rpe_rotation_deg_per_frame"] = statsJson(rpe.rotation);
    for (auto& p : e.aligned) p.T_wc = ate.T_gt_est * p.T_wc;
    std::ostringstream t;
    t << std::fixed << std::setprecision(4) << "   ATE RMSE " << ate.translation.rmse << " m";
    e.title = t.str();
    std::cout << "ATE RMSE " << ate.translation.rmse << " m over " << ate.translation.count
              << " frames (with scale: " << sim.translation.rmse << " m, scale " << sim.scale
              << "); RPE " << rpe.translation.rmse << " m, " << rpe.rotation.rmse
              << " deg per frame\n";
  } catch (const std::exception& error) {
    e.error = file + " does not fit the run: " + error.what();
  }
  return e;
}

Json summaryJson(const Options& options, const SystemConfig& config, const TumSequence& sequence,
                 const System& system, const RunCounts& c, size_t tracked) {
  Json json = {{"sequence", sequence.folder()},
               {"config", options.config},
               {"frames", c.frames},
               {"tracked", tracked},
               {"lost", c.lost},
               {"keyframes", system.map().numKeyFrames()},
               {"keyframes_created", c.keyframes_created},
               {"keyframes_culled", c.keyframes_culled},
               {"map_points", system.map().numMapPoints()},
               {"map_points_culled", c.points_culled},
               {"map_points_merged", c.points_merged},
               {"observations_fused", c.observations_fused},
               {"segmenter", options.segmentation.kind},
               {"dynamic_mode", toString(config.dynamic.mode)},
               {"dynamic_features_dropped", c.dynamic_features},
               {"segmentation_ms_median", rounded(median(c.segment_ms, 0.0))}};
  return json;
}

Json linesJson(const SystemConfig& config, const System& system, const RunCounts& c) {
  return {{"enabled", config.lines.enabled},
          {"balance", toString(config.lines.balance)},
          {"map_lines", system.map().numMapLines()},
          {"line_inliers_mean", rounded(c.frames > 0 ? c.line_inliers / c.frames : 0.0)},
          {"lines_ms_median", rounded(median(c.lines_ms, 0.0))},
          {"lines_ms_p95", rounded(percentile(c.lines_ms, 0.95, 0.0))}};
}

Json classificationJson(const FeatureClassification& classification) {
  return {{"walker_features", classification.walkerFeatures()},
          {"walker_kept_share", rounded(classification.walkerKeptShare())},
          {"walker_inlier_share", rounded(classification.walkerInlierShare())},
          {"static_features", classification.staticFeatures()},
          {"static_dropped_share", rounded(classification.staticDroppedShare())}};
}

// Starts the system in the map saved in --map; what summary.json says of it.
Json loadSavedMap(System& system, const Options& options) {
  Stopwatch watch;
  system.loadMap(options.map, options.localisation_only);
  return {{"loaded", options.map},
          {"load_ms", rounded(watch.elapsedMs())},
          {"localisation_only", options.localisation_only},
          {"keyframes_loaded", system.map().numKeyFrames()},
          {"map_points_loaded", system.map().numMapPoints()},
          {"map_lines_loaded", system.map().numMapLines()}};
}

// --save-map: the map file, its size and the time it took; an error goes with the others.
Json saveMap(const System& system, const std::string& folder, FileWrites& outputs) {
  Stopwatch watch;
  if (!outputs.attempt([&] { system.saveMap(folder); })) return nullptr;
  const fs::path file = fs::path(folder) / System::kMapFileName;
  return {{"file", file.string()},
          {"bytes", fs::file_size(file)},
          {"save_ms", rounded(watch.elapsedMs())}};
}

SystemConfig runConfig(const Options& options) {
  SystemConfig config = loadConfig(options.config);
  if (options.no_lines) config.lines.enabled = false;
  if (options.no_loop) config.loop.enabled = false;
  if (!options.dynamic.empty()) config.dynamic.mode = parseDynamicMode(options.dynamic);
  return config;
}

// One run over a TUM folder: tracks every frame, then writes the trajectories, the maps and
// summary.json. A frame that cannot be read ends the tracking, but what was tracked so far is
// still written; every output is kept in memory or written whole (FileWrites).
class TumRun {
 public:
  explicit TumRun(const Options& options);
  int run() {
    trackFrames();
    finishMapping();
    writeTrackingOutputs();
    Json json = summarise();
    finishMapsAndPlot(json);
    writeSummary(json);
    return report();
  }

 private:
  void trackFrames();
  // Where the frames around a --kidnap / --cover gap were and how tracking took them.
  void noteGap(size_t i, double stamp, const FrameResult& r);
  Json gapJson() const;
  std::vector<Instance> segment(const RgbdImages& images);
  void scoreAgainstGroundTruth(const RgbdImages& images, const std::vector<Instance>& instances,
                               const FrameResult& r);
  void saveImage(size_t i, const RgbdImages& images, const FrameResult& r);
  void takeMapped(const std::vector<MappedKeyFrame>& mapped);
  void finishMapping();
  // timing.csv, the trajectories and, with --save-map, the map.
  void writeTrackingOutputs();
  Json summarise();
  void finishMapsAndPlot(Json& json);
  void writeSummary(Json& json);
  int report() const;

  const Options& options_;
  SystemConfig config_;
  const TumSequence sequence_;
  const fs::path out_;
  std::unique_ptr<Segmenter> segmenter_;
  std::unique_ptr<LiveSegmenter> live_;
  // Where there are ground-truth masks of the moving objects, the dynamic rejection and the
  // dense maps are scored against them.
  std::unique_ptr<MaskFolderSegmenter> walker_masks_;
  // Offline with the sequence's own masks as segmenter, its instances are the ground truth:
  // no second read of every mask.
  bool segmenter_is_ground_truth_ = false;
  FeatureClassification classification_;
  std::unique_ptr<System> system_;
  Json map_json_ = Json::object();
  std::unique_ptr<DenseMappingWorker> dense_;
  FileWrites outputs_;
  std::ostringstream timing_;  // kept in memory and written at the end like every output
  RunCounts counts_;
  std::string failure_;
  std::chrono::steady_clock::time_point start_;
  double first_stamp_ = -1.0;
  std::vector<std::shared_ptr<const LoopCorrection>> corrections_;
  // The people's pixels of each keyframe's frame, until the mapping side hands its packet on.
  std::map<long, cv::Mat> keyframe_walkers_;
  Trajectory trajectory_;  // derived from the keyframes' final poses: taken once
  Evaluation evaluation_;
  struct GapLog {
    double start_stamp = 0.0, end_stamp = 0.0;  // the last frame before it, the first after
    long lost_after = 0;                        // frames after it before one was tracked
    bool tracked_after = false;
    std::vector<double> relocalised;  // stamps of the frames tracking relocalised in
  } gap_;
};

TumRun::TumRun(const Options& options)
    : options_(options),
      config_(runConfig(options)),
      sequence_(options.sequence),
      out_(options.out) {
  fs::create_directories(out_);
  removeEarlierRun(out_);
  // Offline, every frame is segmented before it is tracked: runs are reproducible.
  segmenter_ = options.segmentation.make(config_.segmentation, sequence_.folder());
  if (!segmenter_) config_.dynamic.mode = modeWithoutSegmenter(config_.dynamic.mode);
  if (options.segment_lag > 0)
    segmenter_ = std::make_unique<LaggedSegmenter>(std::move(segmenter_),
                                                   static_cast<int>(options.segment_lag));
  if (options.live)
    live_ =
        std::make_unique<LiveSegmenter>(std::move(segmenter_), config_.segmentation.live_threads);
  walker_masks_ = groundTruthMasks(options, sequence_);
  segmenter_is_ground_truth_ =
      walker_masks_ && !options.live && options.segment_lag == 0 &&
      options.segmentation.kind == "masks" &&
      (options.ground_truth_masks.empty() || options.ground_truth_masks == sequence_.folder());
  if (options.save_images > 0) fs::create_directories(out_ / "images");
  // The tracker works in a copy of the map of its own, as the tracking process of the
  // two-process split (issue 17); --realtime: the mapping side on a thread of its own.
  system_ = std::make_unique<System>(
      config_, options.realtime ? MappingMode::kSplitOwnThread : MappingMode::kSplit);
  if (!options.map.empty()) map_json_ = loadSavedMap(*system_, options);
  if (options.gap && static_cast<size_t>(options.gap->to) >= sequence_.size())
    throw std::invalid_argument("the gap ends at frame " + std::to_string(options.gap->to) +
                                " but the sequence has " + std::to_string(sequence_.size()) +
                                " frames: nothing left after it");
  if (config_.dense.enabled) dense_ = std::make_unique<DenseMappingWorker>(config_.dense);
  timing_ << kTimingHeader;
}

void TumRun::trackFrames() {
  const size_t n = options_.max_frames >= 0
                       ? std::min(sequence_.size(), static_cast<size_t>(options_.max_frames))
                       : sequence_.size();
  start_ = std::chrono::steady_clock::now();
  for (size_t i = 0; i < n; ++i) {
    const bool in_gap = options_.gap && options_.gap->holds(i);
    if (in_gap && !options_.gap->black) continue;  // kidnapped: the camera is elsewhere
    FrameResult r;
    RgbdImages images;
    try {
      images = sequence_.load(i, config_.camera.depth_factor);
      if (in_gap) {  // covered: nothing to see
        images.rgb.setTo(cv::Scalar::all(0));
        images.depth.setTo(cv::Scalar::all(0));
      }
      const std::vector<Instance> instances = segment(images);
      r = system_->process(images, instances);
      scoreAgainstGroundTruth(images, instances, r);
      takeMapped(r.mapped);
    } catch (const std::exception& e) {
      failure_ = e.what();
      return;
    }
    saveImage(i, images, r);
    noteGap(i, images.stamp, r);
    counts_.add(r);
    writeTimingRow(timing_, r, *system_);
  }
}

void TumRun::noteGap(size_t i, double stamp, const FrameResult& r) {
  if (!options_.gap) return;
  const bool ok = r.tracking.state == TrackingState::kOk;
  if (ok && r.tracking.method == "reloc") gap_.relocalised.push_back(stamp);
  if (static_cast<long>(i) + 1 == options_.gap->from) gap_.start_stamp = stamp;
  if (static_cast<long>(i) == options_.gap->to) gap_.end_stamp = stamp;
  if (static_cast<long>(i) < options_.gap->to || gap_.tracked_after) return;
  gap_.tracked_after = ok;
  gap_.lost_after += !ok;
}

Json TumRun::gapJson() const {
  const FrameGap& gap = *options_.gap;
  Json json = {{"kind", gap.black ? "cover" : "kidnap"}, {"from", gap.from}, {"to", gap.to}};
  json["frames_until_tracked"] = gap_.tracked_after ? Json(gap_.lost_after) : Json(nullptr);
  if (!sequence_.hasGroundTruth()) return json;
  try {
    const GapReport g = evaluateGap(sequence_.groundTruth(), trajectory_, gap_.start_stamp,
                                    gap_.end_stamp, gap_.relocalised);
    if (g.relocalised) {
      json["first_error_m"] = rounded(g.first_error_m);
      json["first_error_deg"] = rounded(g.first_error_deg);
    }
    json["ate_after"] = statsJson(g.after);
    json["relocalisations"] = g.relocalisations;
    json["wrong_relocalisations"] = g.wrong_relocalisations;
  } catch (const std::exception& e) {
    json["error"] = e.what();
  }
  return json;
}

std::vector<Instance> TumRun::segment(const RgbdImages& images) {
  if (live_) {
    // A camera delivers the frame at its stamp: wait for it, never for the network.
    if (first_stamp_ < 0) first_stamp_ = images.stamp;
    std::this_thread::sleep_until(start_ +
                                  std::chrono::duration<double>(images.stamp - first_stamp_));
    live_->submit(images);
    return live_->instancesFor(images);
  }
  if (!segmenter_) return {};
  Stopwatch watch;
  std::vector<Instance> instances = segmenter_->segment(images);
  counts_.segment_ms.push_back(watch.elapsedMs());
  return instances;
}

void TumRun::scoreAgainstGroundTruth(const RgbdImages& images,
                                     const std::vector<Instance>& instances, const FrameResult& r) {
  if (!walker_masks_) return;
  const cv::Size size = images.rgb.size();
  const cv::Mat walkers = segmenter_is_ground_truth_
                              ? walkerPixels(instances, size, config_.dynamic)
                              : walkerPixels(walker_masks_->segment(images), size, config_.dynamic);
  classification_.add(r.features, walkers);
  if (dense_ && r.tracking.new_keyframe) keyframe_walkers_[r.frame_id] = walkers;
}

void TumRun::saveImage(size_t i, const RgbdImages& images, const FrameResult& r) {
  if (options_.save_images <= 0 || i % options_.save_images != 0) return;
  char name[32];
  std::snprintf(name, sizeof(name), "%06ld.jpg", r.frame_id);
  outputs_.attempt([&] {
    writeImageFile((out_ / "images" / name).string(),
                   drawTrackingImage(images.rgb, r, r.instances));
  });
}

void TumRun::takeMapped(const std::vector<MappedKeyFrame>& mapped) {
  for (const MappedKeyFrame& m : mapped) {
    counts_.add(m);
    if (m.loop_correction) corrections_.push_back(m.loop_correction);
    if (!dense_) continue;
    if (m.packet) {
      const auto walkers = keyframe_walkers_.find(m.packet->frame_id);
      dense_->push(m.packet, walkers != keyframe_walkers_.end() ? walkers->second : cv::Mat());
      if (walkers != keyframe_walkers_.end()) keyframe_walkers_.erase(walkers);
    }
    dense_->follow(*m.map_update);
  }
}

void TumRun::finishMapping() {
  try {
    takeMapped(system_->finishMapping());
  } catch (const std::exception& e) {
    if (failure_.empty()) failure_ = e.what();
  }
}

void TumRun::writeTrackingOutputs() {
  outputs_.attempt([&] { writeTextFileAtomically((out_ / "timing.csv").string(), timing_.str()); });
  trajectory_ = system_->cameraTrajectory();
  outputs_.attempt(
      [&] { writeTumTrajectory((out_ / "CameraTrajectory.txt").string(), trajectory_); });
  outputs_.attempt([&] {
    writeTumTrajectory((out_ / "KeyFrameTrajectory.txt").string(), system_->keyFrameTrajectory());
  });
  if (!options_.save_map.empty())
    map_json_["saved"] = saveMap(*system_, options_.save_map, outputs_);
}

Json TumRun::summarise() {
  Json json = summaryJson(options_, config_, sequence_, *system_, counts_, trajectory_.size());
  // In a loaded map the frames before the first tracked one are those relocalisation took.
  if (!options_.map.empty()) map_json_["first_tracked_frame"] = counts_.first_tracked;
  if (!map_json_.empty()) json["map"] = map_json_;
  if (live_)
    json["live"] = {{"segmented_frames", live_->segmentedFrames()},
                    {"mask_age_mean_s", rounded(live_->meanAgeSeconds())}};
  if (walker_masks_) json["feature_classification"] = classificationJson(classification_);
  json["lines"] = linesJson(config_, *system_, counts_);
  json["tracking_ms_median"] = rounded(median(counts_.total_ms, 0.0));
  json["tracking_ms_p95"] = rounded(percentile(counts_.total_ms, 0.95, 0.0));
  json["peak_rss_mb"] = nullptr;  // set once the dense maps and the plot are done
  json["loops"] = loopsJson(*system_, corrections_);
  json["mapping"] = {{"own_thread", options_.realtime},
                     {"longest_queue", system_->longestMappingQueue()},
                     {"keyframes_held_back", counts_.keyframes_held_back}};
  evaluation_ = evaluate(sequence_, trajectory_);
  json.update(evaluation_.fields);
  if (options_.gap) json["gap"] = gapJson();
  return json;
}

void TumRun::finishMapsAndPlot(Json& json) {
  const std::string title =
      "ply_slam  " + fs::path(sequence_.folder()).filename().string() + evaluation_.title;
  if (dense_) {
    Json grid;
    json["dense"] = finishDenseMaps(*dense_, *system_, config_, trajectory_, out_, title,
                                    walker_masks_ != nullptr, outputs_, grid);
    if (!grid.is_null()) json["grid"] = grid;
  }
  if (!failure_.empty()) json["error"] = failure_;
  if (!evaluation_.error.empty()) json["evaluation_error"] = evaluation_.error;
  outputs_.attempt([&] {
    writeTrajectoryPlot((out_ / "trajectory.png").string(), sequence_.groundTruth(),
                        evaluation_.aligned, title);
  });
}

void TumRun::writeSummary(Json& json) {
  json["peak_rss_mb"] = rounded(peakRssMb());
  if (!outputs_.failures().empty()) json["output_errors"] = outputs_.messages();
  outputs_.attempt(
      [&] { writeTextFileAtomically((out_ / "summary.json").string(), json.dump(2) + "\n"); });
}

int TumRun::report() const {
  std::cout << "frames " << counts_.frames << ", tracked " << trajectory_.size() << ", lost "
            << counts_.lost << ", keyframes " << system_->map().numKeyFrames() << ", map points "
            << system_->map().numMapPoints() << "\n"
            << "tracking ms median " << median(counts_.total_ms, 0.0) << ", p95 "
            << percentile(counts_.total_ms, 0.95, 0.0) << "\n"
            << "outputs in " << fs::absolute(out_).string() << "\n";
  if (!failure_.empty()) {
    std::cerr << "ply_slam_tum: stopped after " << counts_.frames << " frames: " << failure_
              << "\n";
    return 1;
  }
  if (!outputs_.failures().empty()) {
    for (const auto& failure : outputs_.failures())
      std::cerr << "ply_slam_tum: " << failure.message << "\n";
    std::cerr << "ply_slam_tum: " << outputs_.summaryText() << "\n";
    return 1;
  }
  if (!evaluation_.error.empty()) {
    std::cerr << "ply_slam_tum: warning: every output written, but " << evaluation_.error << "\n";
    return kExitEvaluationFailed;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return ply_slam::runTool("ply_slam_tum", kUsage, [&] {
    const Options options = parse(argc, argv);
    return TumRun(options).run();
  });
}
