// Offline run of ply_slam on a TUM RGB-D folder:
//   ply_slam_tum --sequence DIR --config FILE --out DIR [--segmenter none|masks|yolo]
//                [--model ONNX --input WxH] [--dynamic off|geometric|semantic|full] [--live]
//                [--save-images N] [--max-frames N] [--no-lines] [--ground-truth-masks DIR]
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
#include <iomanip>
#include <iostream>
#include <memory>
#include <opencv2/imgcodecs.hpp>
#include <sstream>
#include <thread>

#include "ply_slam/common/command_line.h"
#include "ply_slam/common/config.h"
#include "ply_slam/common/number_text.h"
#include "ply_slam/common/stopwatch.h"
#include "ply_slam/dense/dense_mapping_worker.h"
#include "ply_slam/dense/grid_map_files.h"
#include "ply_slam/dense/grid_renderer.h"
#include "ply_slam/dense/map_export.h"
#include "ply_slam/dense/occupancy_grid_builder.h"
#include "ply_slam/dense/top_view_renderer.h"
#include "ply_slam/eval/feature_classification.h"
#include "ply_slam/eval/trajectory_metrics.h"
#include "ply_slam/eval/trajectory_plot.h"
#include "ply_slam/io/tum_sequence.h"
#include "ply_slam/io/tum_trajectory_file.h"
#include "ply_slam/semantic/live_segmenter.h"
#include "ply_slam/semantic/mask_folder_segmenter.h"
#include "ply_slam/semantic/yolo_v8_seg.h"
#include "ply_slam/system/system.h"
#include "ply_slam/system/tracking_image.h"

namespace fs = std::filesystem;
using namespace ply_slam;

namespace {

struct Options {
  std::string sequence, config, out;
  long max_frames = -1;
  std::string segmenter = "none";
  std::string model;                      // overrides the config's segmentation.model
  int input_width = 0, input_height = 0;  // and its input size
  bool no_lines = false;                  // overrides lines.enabled of the config
  bool no_loop = false;                   // overrides loop.enabled of the config
  std::string dynamic;                    // overrides dynamic.mode of the config
  bool live = false;                      // frames at their own pace, segmentation beside
  long save_images = 0;                   // every N frames a tracking image; 0 = none
  std::string ground_truth_masks;         // walker masks: feature classification, ghost count
};

[[noreturn]] void usage(const std::string& error) {
  std::cerr
      << "ply_slam_tum: " << error << "\n"
      << "usage: ply_slam_tum --sequence DIR --config FILE --out DIR"
         " [--segmenter none|masks|yolo] [--model ONNX --input WxH]"
         " [--dynamic off|geometric|semantic|full] [--live] [--save-images N] [--max-frames N]"
         " [--no-lines] [--no-loop]\n"
         "  --no-lines: points only, whatever lines.enabled says\n"
         "  --no-loop: no place recognition nor loop closure, whatever loop.enabled says\n"
         "  --dynamic: how dynamic features are rejected (default: the config's dynamic.mode)\n"
         "  --live: play the frames at their recorded rate and segment on a second thread, as\n"
         "          the ROS node does (results then depend on timing)\n"
         "  --save-images N: write every N-th tracking image to DIR/images\n"
         "  --segmenter masks: instance masks from DIR/masks and DIR/instances.txt\n"
         "  --segmenter yolo: YOLOv8-seg, model from the config's segmentation section or"
         " --model/--input\n"
         "  --ground-truth-masks DIR: count dense points and octree voxels from the people of\n"
         "    DIR/masks (default: the sequence's own masks/ when it has them)\n";
  std::exit(2);
}

long parseCount(const std::string& option, const std::string& text) {
  const std::optional<long> value = parseWholeNumber(text, 0, 1000000000L);
  if (!value) usage(option + " needs a whole number >= 0, got '" + text + "'");
  return *value;
}

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--no-lines" || arg == "--live" || arg == "--no-loop") {
      (arg == "--live" ? o.live : arg == "--no-loop" ? o.no_loop : o.no_lines) = true;
      continue;
    }
    if (i + 1 >= argc) usage("missing value after " + arg);
    const std::string value = argv[++i];
    if (arg == "--sequence")
      o.sequence = value;
    else if (arg == "--config")
      o.config = value;
    else if (arg == "--out")
      o.out = value;
    else if (arg == "--segmenter")
      o.segmenter = value;
    else if (arg == "--model")
      o.model = value;
    else if (arg == "--input") {
      if (std::sscanf(value.c_str(), "%dx%d", &o.input_width, &o.input_height) != 2 ||
          o.input_width <= 0 || o.input_height <= 0)
        usage("--input needs WxH, e.g. 320x320");
    } else if (arg == "--ground-truth-masks")
      o.ground_truth_masks = value;
    else if (arg == "--max-frames")
      o.max_frames = parseCount(arg, value);
    else if (arg == "--dynamic")
      o.dynamic = value;
    else if (arg == "--save-images")
      o.save_images = parseCount(arg, value);
    else
      usage("unknown option " + arg);
  }
  if (o.segmenter != "none" && o.segmenter != "masks" && o.segmenter != "yolo")
    usage("unknown segmenter '" + o.segmenter + "' (none, masks or yolo)");
  if (!o.dynamic.empty()) try {
      parseDynamicMode(o.dynamic);
    } catch (const std::invalid_argument&) {
      usage("unknown dynamic mode '" + o.dynamic + "' (off, geometric, semantic or full)");
    }
  if (o.live && o.segmenter == "none") usage("--live needs a segmenter");
  if (o.sequence.empty() || o.config.empty() || o.out.empty())
    usage("--sequence, --config and --out are required");
  return o;
}

double percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const size_t k = std::min(v.size() - 1, static_cast<size_t>(std::ceil(q * v.size())) - (q > 0));
  return v[k];
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

std::string jsonEscape(const std::string& text) {
  std::string out;
  for (const char c : text) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out;
}

std::string jsonStats(const ErrorStats& s) {
  std::ostringstream out;
  out << std::setprecision(6) << "{\"pairs\": " << s.count << ", \"rmse\": " << s.rmse
      << ", \"mean\": " << s.mean << ", \"median\": " << s.median << ", \"max\": " << s.max << "}";
  return out.str();
}

// Dense and semantic octree maps (issue #7) ---------------------------------------------------

// The ground-truth masks of the moving things (active classes) in one frame, undilated: what
// a ghost in the maps would come from.
cv::Mat walkerPixels(const std::vector<Instance>& ground_truth, const cv::Size& size,
                     const DynamicParams& dynamic) {
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

// Drains the worker, re-places keyframes at their final poses, writes the maps and
// map_top.png; returns the summary.json fields.
// The occupancy grid from the octree: map.pgm, map.yaml (in the floor frame) and grid.png;
// returns the summary's "grid" member.
std::string writeGrid(const SemanticOctree& octree, const SystemConfig& config,
                      const Trajectory& trajectory, const fs::path& out, const std::string& title) {
  Stopwatch watch;
  const OccupancyGridBuilder builder(
      config.grid, OccupancyGridBuilder::labelsOf(octree.palette(), config.dynamic.active_classes));
  const OccupancyGrid grid = builder.build(octree, trajectory);
  const double ms = watch.elapsedMs();
  writeGridMap(out.string(), grid);
  GridRenderer().write((out / "grid.png").string(), grid, trajectory,
                       title + "   occupancy grid (" + grid.floor().method + " floor)");
  const Eigen::Vector3d up = grid.floor().T_world_floor.linear().col(2);
  // The first camera's height above the floor found: a check against the rig's height.
  const double camera_height =
      trajectory.empty()
          ? 0.0
          : (grid.floor().T_world_floor.inverse() * trajectory.front().T_wc.translation()).z();
  std::ostringstream json;
  json << ",\n  \"grid\": {\"width\": " << grid.width() << ", \"height\": " << grid.height()
       << ", \"resolution\": " << grid.resolution()
       << ", \"occupied\": " << grid.count(OccupancyGrid::kOccupied)
       << ", \"free\": " << grid.count(OccupancyGrid::kFree)
       << ", \"unknown\": " << grid.count(OccupancyGrid::kUnknown) << ", \"floor\": \""
       << grid.floor().method << "\", \"floor_support\": " << grid.floor().support << ", \"up\": ["
       << up.x() << ", " << up.y() << ", " << up.z()
       << "], \"first_camera_height\": " << camera_height << ", \"ms\": " << ms << "}";
  std::cout << "occupancy grid " << grid.width() << " x " << grid.height() << " cells, "
            << grid.count(OccupancyGrid::kOccupied) << " occupied, "
            << grid.count(OccupancyGrid::kFree) << " free (" << grid.floor().method << " floor)\n";
  return json.str();
}

std::string finishDenseMaps(DenseMappingWorker& dense, const System& system,
                            const SystemConfig& config, const Trajectory& trajectory,
                            const fs::path& out, const std::string& title, bool counted_walkers) {
  MapUpdate final_poses;
  for (const auto& keyframe : system.map().keyFrames())
    if (keyframe) final_poses.keyframes.push_back({keyframe->id, keyframe->T_wc()});
  dense.push(final_poses);
  dense.finish();
  const std::vector<double> ms = dense.keyFrameMs();
  std::ostringstream json;
  dense.withMaps([&](DenseMap& map, const SemanticOctree& octree) {
    Stopwatch global_watch;
    const size_t points = map.numGlobalPoints();
    const double global_ms = global_watch.elapsedMs();
    writeDenseMaps(out.string(), map, octree);
    const std::vector<SemanticOctree::Voxel> voxels = octree.occupiedVoxels();
    TopViewRenderer().write((out / "map_top.png").string(), voxels, trajectory,
                            TopViewRenderer::upFromTrajectory(trajectory), octree.palette(),
                            title + "   semantic octree, top view");
    size_t walker_majority = 0, walker_any = 0;
    for (const auto& v : voxels) {
      walker_majority += 2 * v.tagged > v.hits;
      walker_any += v.tagged > 0;
    }
    json << ",\n  \"dense\": {\"keyframes\": " << map.numKeyFrames() << ", \"points\": " << points
         << ", \"points_before_octree_filter\": " << map.numUnfilteredPoints()
         << ", \"occupied_voxels\": " << voxels.size()
         << ", \"ms_per_keyframe_median\": " << percentile(ms, 0.5)
         << ", \"ms_per_keyframe_p95\": " << percentile(ms, 0.95)
         << ", \"global_cloud_ms\": " << global_ms << ", \"max_queue\": " << dense.maxQueueLength()
         << ", \"rejected_packets\": " << dense.rejectedPackets()
         << ", \"cloud_bytes\": " << map.memoryBytes()
         << ", \"octree_bytes\": " << octree.memoryBytes()
         << ", \"memory_bytes\": " << map.memoryBytes() + octree.memoryBytes();
    if (counted_walkers) {
      const long walker_points = map.taggedPoints();
      const long unfiltered = map.taggedPoints(true);
      json << ",\n    \"walkers\": {\"points\": " << walker_points
           << ", \"points_share\": " << (points ? double(walker_points) / points : 0.0)
           << ", \"points_before_octree_filter\": " << unfiltered
           << ", \"points_before_octree_filter_share\": "
           << double(unfiltered) / std::max<size_t>(1, map.numUnfilteredPoints())
           << ", \"voxels_majority\": " << walker_majority << ", \"voxels_majority_share\": "
           << (voxels.empty() ? 0.0 : double(walker_majority) / voxels.size())
           << ", \"voxels_any\": " << walker_any << ", \"voxels_any_share\": "
           << (voxels.empty() ? 0.0 : double(walker_any) / voxels.size()) << "}";
    }
    json << "}";
    if (config.grid.enabled) json << writeGrid(octree, config, trajectory, out, title);
    std::cout << "dense map " << points << " points, octree " << voxels.size()
              << " occupied voxels; dense+octree ms per keyframe median " << percentile(ms, 0.5)
              << ", p95 " << percentile(ms, 0.95) << "\n";
  });
  if (dense.rejectedPackets() > 0)
    std::cerr << "ply_slam_tum: dense maps left out " << dense.rejectedPackets()
              << " keyframes: " << dense.firstError() << "\n";
  return json.str();
}

// Loop closure's counts and each correction (null when loop closure is off).
std::string loopsJson(const System& system,
                      const std::vector<std::shared_ptr<const LoopCorrection>>& corrections) {
  const LoopClosureCounts* counts = system.loopCounts();
  if (!counts) return "null";
  double pose_graph_ms = 0.0, global_ba_ms = 0.0;
  for (const auto& c : corrections) {
    pose_graph_ms += c->pose_graph.ms;
    global_ba_ms += c->global_ba_ms;
  }
  std::ostringstream json;
  json << "{\"queries\": " << counts->queries << ", \"detected\": " << counts->detected
       << ", \"accepted\": " << counts->accepted << ", \"implausible\": " << counts->implausible
       << ", \"corrected\": " << counts->corrected << ", \"pose_graph_ms\": " << pose_graph_ms
       << ", \"global_ba_ms\": " << global_ba_ms << ", \"corrections\": [";
  for (size_t i = 0; i < corrections.size(); ++i) {
    const LoopCorrection& c = *corrections[i];
    json << (i ? ", " : "") << "{\"query\": " << c.loop.query_id
         << ", \"candidate\": " << c.loop.candidate_id << ", \"moved_m\": " << c.shift.moved_m
         << ", \"turned_deg\": " << c.shift.turned_deg
         << ", \"connected\": " << c.connected_keyframes << ", \"fused\": " << c.fused
         << ", \"loop_links\": " << c.loop_links
         << ", \"pose_graph_iterations\": " << c.pose_graph.iterations
         << ", \"pose_graph_ms\": " << c.pose_graph.ms << ", \"global_ba_ms\": " << c.global_ba_ms
         << ", \"ms\": " << c.ms << "}";
  }
  json << "]}";
  return json.str();
}

int run(const Options& options) {
  SystemConfig config = loadConfig(options.config);
  if (options.no_lines) config.lines.enabled = false;
  if (options.no_loop) config.loop.enabled = false;
  if (!options.dynamic.empty()) config.dynamic.mode = options.dynamic;
  const TumSequence sequence(options.sequence);
  fs::create_directories(options.out);
  const fs::path out(options.out);

  std::unique_ptr<Segmenter> segmenter;
  if (options.segmenter == "masks") {
    segmenter = std::make_unique<MaskFolderSegmenter>(sequence.folder());
  } else if (options.segmenter == "yolo") {
    // Offline, every frame is segmented before it is tracked: runs are reproducible.
    YoloParams yolo = config.segmentation;
    if (!options.model.empty()) yolo.model_path = options.model;
    if (options.input_width > 0) {
      yolo.input_width = options.input_width;
      yolo.input_height = options.input_height;
    }
    segmenter = std::make_unique<YoloV8Seg>(yolo);
  }
  std::unique_ptr<LiveSegmenter> live;
  if (options.live) live = std::make_unique<LiveSegmenter>(std::move(segmenter));
  // Where there are ground-truth masks of the moving objects, the dynamic rejection and the
  // dense maps are scored against them.
  const std::unique_ptr<MaskFolderSegmenter> walker_masks = groundTruthMasks(options, sequence);
  // Offline with the sequence's own masks as segmenter, its instances are the ground truth:
  // no second read of every mask.
  const bool segmenter_is_ground_truth =
      walker_masks && !options.live && options.segmenter == "masks" &&
      (options.ground_truth_masks.empty() || options.ground_truth_masks == sequence.folder());
  FeatureClassification classification;
  if (options.save_images > 0) fs::create_directories(out / "images");
  System system(config);
  std::unique_ptr<DenseMappingWorker> dense;
  if (config.dense.enabled) dense = std::make_unique<DenseMappingWorker>(config.dense);
  std::ofstream timing(out / "timing.csv");
  timing
      << "frame,stamp,state,method,inliers,line_inliers,keyframe,features_ms,lines_ms,tracking_ms,"
         "mapping_ms,total_ms,rss_mb,keyframes,map_points\n";
  std::vector<double> total_ms, lines_ms;
  double line_inliers = 0.0;
  size_t dynamic_features = 0;
  long frames = 0, lost = 0, keyframes_created = 0, keyframes_culled = 0, points_culled = 0;
  const size_t n = options.max_frames >= 0
                       ? std::min(sequence.size(), static_cast<size_t>(options.max_frames))
                       : sequence.size();
  // A frame that cannot be read ends the run, but what was tracked so far is still written.
  std::string failure;
  const auto start = std::chrono::steady_clock::now();
  double first_stamp = -1.0;
  std::vector<double> segment_ms;
  std::vector<std::shared_ptr<const LoopCorrection>> corrections;
  for (size_t i = 0; i < n && failure.empty(); ++i) {
    FrameResult r;
    std::vector<Instance> instances;
    RgbdImages images;
    try {
      images = sequence.load(i, config.camera.depth_factor);
      if (live) {
        // A camera delivers the frame at its stamp: wait for it, never for the network.
        if (first_stamp < 0) first_stamp = images.stamp;
        std::this_thread::sleep_until(start +
                                      std::chrono::duration<double>(images.stamp - first_stamp));
        live->submit(images);
        instances = live->instancesFor(images);
      } else if (segmenter) {
        Stopwatch watch;
        instances = segmenter->segment(images);
        segment_ms.push_back(watch.elapsedMs());
      }
      r = system.process(images, instances);
      const cv::Mat walkers =
          !walker_masks ? cv::Mat()
          : segmenter_is_ground_truth
              ? walkerPixels(instances, images.rgb.size(), config.dynamic)
              : walkerPixels(walker_masks->segment(images), images.rgb.size(), config.dynamic);
      if (walker_masks) classification.add(r.features, walkers);
      if (dense) dense->erase(r.culled_keyframes);
      if (dense && r.keyframe_packet) dense->push(r.keyframe_packet, walkers);
      if (dense && r.loop_correction) dense->push(r.loop_correction->update);
      if (r.loop_correction) corrections.push_back(r.loop_correction);
    } catch (const std::exception& e) {
      failure = e.what();
      break;
    }
    if (options.save_images > 0 && i % options.save_images == 0) {
      char name[32];
      std::snprintf(name, sizeof(name), "%06ld.jpg", r.frame_id);
      cv::imwrite((out / "images" / name).string(), drawTrackingImage(images.rgb, r, r.instances));
    }
    ++frames;
    if (r.tracking.state != TrackingState::kOk) ++lost;
    keyframes_created += r.tracking.new_keyframe != nullptr;
    keyframes_culled += static_cast<long>(r.culled_keyframes.size());
    points_culled += r.culled_points;
    total_ms.push_back(r.timing.total_ms);
    lines_ms.push_back(r.timing.lines_ms);
    line_inliers += r.tracking.line_inliers;
    dynamic_features += r.dynamic_features;
    timing << r.frame_id << ',' << std::fixed << std::setprecision(6) << r.stamp << ','
           << toString(r.tracking.state) << ',' << r.tracking.method << ',' << r.tracking.inliers
           << ',' << r.tracking.line_inliers << ',' << (r.tracking.new_keyframe != nullptr) << ','
           << std::setprecision(3) << r.timing.features_ms << ',' << r.timing.lines_ms << ','
           << r.timing.tracking_ms << ',' << r.timing.mapping_ms << ',' << r.timing.total_ms << ','
           << std::setprecision(1) << currentRssMb() << ',' << system.map().numKeyFrames() << ','
           << system.map().numMapPoints() << '\n';
  }

  // Derived from the keyframes' final poses: taken once.
  const Trajectory trajectory = system.cameraTrajectory();
  writeTumTrajectory((out / "CameraTrajectory.txt").string(), trajectory);
  writeTumTrajectory((out / "KeyFrameTrajectory.txt").string(), system.keyFrameTrajectory());

  std::ostringstream json;
  json << std::setprecision(6) << "{\n  \"sequence\": \"" << jsonEscape(sequence.folder())
       << "\",\n  \"config\": \"" << jsonEscape(options.config) << "\",\n"
       << "  \"frames\": " << frames << ",\n  \"tracked\": " << trajectory.size()
       << ",\n  \"lost\": " << lost << ",\n  \"keyframes\": " << system.map().numKeyFrames()
       << ",\n  \"keyframes_created\": " << keyframes_created
       << ",\n  \"keyframes_culled\": " << keyframes_culled
       << ",\n  \"map_points\": " << system.map().numMapPoints()
       << ",\n  \"map_points_culled\": " << points_culled << ",\n"
       << "  \"segmenter\": \"" << options.segmenter << "\",\n"
       << "  \"dynamic_mode\": \"" << config.dynamic.mode << "\",\n"
       << "  \"dynamic_features_dropped\": " << dynamic_features << ",\n"
       << "  \"segmentation_ms_median\": " << percentile(segment_ms, 0.5) << ",\n";
  if (live)
    json << "  \"live\": {\"segmented_frames\": " << live->segmentedFrames()
         << ", \"mask_age_mean_s\": " << live->meanAgeSeconds() << "},\n";
  if (walker_masks)
    json << "  \"feature_classification\": {\"walker_features\": "
         << classification.walkerFeatures()
         << ", \"walker_kept_share\": " << classification.walkerKeptShare()
         << ", \"walker_inlier_share\": " << classification.walkerInlierShare()
         << ", \"static_features\": " << classification.staticFeatures()
         << ", \"static_dropped_share\": " << classification.staticDroppedShare() << "},\n";
  json << "  \"lines\": {\"enabled\": " << (config.lines.enabled ? "true" : "false")
       << ", \"balance\": \"" << config.lines.balance
       << "\", \"map_lines\": " << system.map().numMapLines()
       << ", \"line_inliers_mean\": " << (frames > 0 ? line_inliers / frames : 0.0)
       << ", \"lines_ms_median\": " << percentile(lines_ms, 0.5)
       << ", \"lines_ms_p95\": " << percentile(lines_ms, 0.95) << "},\n"
       << "  \"tracking_ms_median\": " << percentile(total_ms, 0.5) << ",\n"
       << "  \"tracking_ms_p95\": " << percentile(total_ms, 0.95) << ",\n"
       << "  \"peak_rss_mb\": " << peakRssMb();
  json << ",\n  \"loops\": " << loopsJson(system, corrections);

  std::string title = "ply_slam  " + fs::path(sequence.folder()).filename().string();
  Trajectory aligned = trajectory;
  if (sequence.hasGroundTruth() && trajectory.size() >= 3) {
    const AteResult ate = computeAte(sequence.groundTruth(), trajectory);
    const RpeResult rpe = computeRpeFrames(sequence.groundTruth(), trajectory, 1);
    json << ",\n  \"ate\": " << jsonStats(ate.translation)
         << ",\n  \"rpe_translation_per_frame\": " << jsonStats(rpe.translation)
         << ",\n  \"rpe_rotation_deg_per_frame\": " << jsonStats(rpe.rotation);
    for (auto& p : aligned) p.T_wc = ate.T_gt_est * p.T_wc;
    std::ostringstream t;
    t << std::fixed << std::setprecision(4) << "   ATE RMSE " << ate.translation.rmse << " m";
    title += t.str();
    std::cout << "ATE RMSE " << ate.translation.rmse << " m over " << ate.translation.count
              << " frames; RPE " << rpe.translation.rmse << " m, " << rpe.rotation.rmse
              << " deg per frame\n";
  }
  if (dense)
    json << finishDenseMaps(*dense, system, config, trajectory, out, title,
                            walker_masks != nullptr);
  if (!failure.empty()) json << ",\n  \"error\": \"" << jsonEscape(failure) << "\"";
  json << "\n}\n";
  std::ofstream(out / "summary.json") << json.str();
  writeTrajectoryPlot((out / "trajectory.png").string(), sequence.groundTruth(), aligned, title);

  std::cout << "frames " << frames << ", tracked " << trajectory.size() << ", lost " << lost
            << ", keyframes " << system.map().numKeyFrames() << ", map points "
            << system.map().numMapPoints() << "\n"
            << "tracking ms median " << percentile(total_ms, 0.5) << ", p95 "
            << percentile(total_ms, 0.95) << "\n"
            << "outputs in " << fs::absolute(out).string() << "\n";
  if (!failure.empty()) {
    std::cerr << "ply_slam_tum: stopped after " << frames << " frames: " << failure << "\n";
    return 1;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const Options options = parse(argc, argv);
  return ply_slam::runReportingErrors("ply_slam_tum", [&] { return run(options); });
}
