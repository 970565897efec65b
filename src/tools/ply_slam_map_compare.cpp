// ply_slam_map_compare: how much a semantic octree built from estimated keyframe poses agrees
// with the one built from ground-truth poses, on the same images.
//   ply_slam_map_compare --sequence DIR --config FILE --keyframes KeyFrameTrajectory.txt
//                        [--clock-offset auto|SECONDS] [--out DIR]
// The ground truth (DIR/groundtruth.txt) is interpolated at the keyframe stamps plus the
// clock offset and rigidly aligned to the estimated keyframe poses (rotations and positions:
// a camera that mostly turns in place, like fr1/rpy, leaves a positions-only alignment's
// rotation undetermined); both octrees use the config's dense section (no segmentation:
// meant for static sequences).
// The camera's stamps and the motion capture's clock need not agree: a few ms are a fraction
// of a degree when the camera turns fast. `auto` (the default) fits the offset, within
// +-30 ms, that minimises the keyframes' rotation error after alignment, and compares the
// octrees both at the recorded stamps and at the fitted offset (TUM's evaluate_ate.py takes
// such an offset by hand, --offset).
// Prints and writes DIR/map_compare.json.
// Exit codes: 0 ok, 1 bad data, 2 usage error.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "ply_slam/common/angles.h"
#include "ply_slam/common/command_line.h"
#include "ply_slam/common/number_text.h"
#include "ply_slam/dense/key_frame_cloud_builder.h"
#include "ply_slam/dense/semantic_octree.h"
#include "ply_slam/dense/voxel_agreement.h"
#include "ply_slam/eval/pose_interpolation.h"
#include "ply_slam/eval/trajectory_metrics.h"
#include "ply_slam/io/atomic_file.h"
#include "ply_slam/io/tum_sequence.h"
#include "ply_slam/io/tum_trajectory_file.h"
#include "ply_slam/system/system_config.h"

namespace fs = std::filesystem;
using namespace ply_slam;
using Json = nlohmann::ordered_json;  // keys in the order written

namespace {

struct Options {
  std::string sequence, config, keyframes, out;
  bool fit_clock_offset = true;
  double clock_offset = 0.0;  // s, added to the keyframe stamps to look up the ground truth
};

const char* const kUsage =
    "usage: ply_slam_map_compare --sequence DIR --config FILE --keyframes FILE"
    " [--clock-offset auto|SECONDS] [--out DIR]\n";

void setOption(Options& o, const std::string& arg, const std::string& value) {
  if (arg == "--sequence")
    o.sequence = value;
  else if (arg == "--config")
    o.config = value;
  else if (arg == "--keyframes")
    o.keyframes = value;
  else if (arg == "--out")
    o.out = value;
  else if (arg == "--clock-offset") {
    o.fit_clock_offset = value == "auto";
    const std::optional<double> seconds = parseRealNumber(value);
    if (!o.fit_clock_offset && !seconds)
      throw UsageError("--clock-offset needs auto or seconds, not " + value);
    if (seconds) o.clock_offset = *seconds;
  }
}

Options parse(int argc, char** argv) {
  Options o;
  CommandLine line;
  line.usage_text = kUsage;
  line.options = {"--sequence", "--config", "--keyframes", "--out", "--clock-offset"};
  line.on_option = [&](const std::string& arg, const std::string& value) {
    setOption(o, arg, value);
  };
  line.parse(argc, argv);
  if (o.sequence.empty() || o.config.empty() || o.keyframes.empty())
    throw UsageError("--sequence, --config and --keyframes are required");
  return o;
}

// The ground-truth pose at `stamp` (poses at most 0.1 s apart around it); throws when the
// stamp is not covered.
Eigen::Isometry3d interpolate(const Trajectory& gt, double stamp) {
  const auto T = interpolatePose(gt, stamp, 0.1);
  if (!T) {
    std::ostringstream s;
    s << std::fixed << std::setprecision(6) << "no ground truth around stamp " << stamp;
    throw std::runtime_error(s.str());
  }
  return *T;
}

// T_est_gt minimising sum |R_est_i - R R_gt_i|_F^2 + |t_est_i - (R t_gt_i + t)|^2 over
// rotation R then translation t: the chordal mean of R_est_i R_gt_i^T, projected onto SO(3).
Eigen::Isometry3d alignPoses(const std::vector<Eigen::Isometry3d>& est,
                             const std::vector<Eigen::Isometry3d>& gt) {
  Eigen::Matrix3d sum = Eigen::Matrix3d::Zero();
  for (size_t i = 0; i < est.size(); ++i) sum += est[i].linear() * gt[i].linear().transpose();
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = nearestRotation(sum);
  Eigen::Vector3d t = Eigen::Vector3d::Zero();
  for (size_t i = 0; i < est.size(); ++i)
    t += est[i].translation() - T.linear() * gt[i].translation();
  T.translation() = t / static_cast<double>(est.size());
  return T;
}

size_t frameAt(const TumSequence& sequence, double stamp) {
  for (size_t i = 0; i < sequence.size(); ++i)
    if (std::abs(sequence.record(i).rgb_stamp - stamp) < 1e-4) return i;
  std::ostringstream s;
  s << std::fixed << std::setprecision(6) << "no rgb frame at keyframe stamp " << stamp;
  throw std::runtime_error(s.str());
}

// The ground truth at the keyframes' stamps + offset, aligned to the keyframes, and how far
// the keyframes are from it.
struct AlignedGroundTruth {
  double offset = 0.0;
  std::vector<Eigen::Isometry3d> T_wc;  // in the estimate's world frame
  double position_rmse = 0.0, rotation_rmse_deg = 0.0;
};

AlignedGroundTruth alignGroundTruth(const Trajectory& gt, const Trajectory& keyframes,
                                    double offset) {
  AlignedGroundTruth a;
  a.offset = offset;
  std::vector<Eigen::Isometry3d> est;
  for (const auto& k : keyframes) {
    a.T_wc.push_back(interpolate(gt, k.stamp + offset));
    est.push_back(k.T_wc);
  }
  const Eigen::Isometry3d T_est_gt = alignPoses(est, a.T_wc);
  double position = 0.0, angle = 0.0;
  for (size_t i = 0; i < est.size(); ++i) {
    a.T_wc[i] = T_est_gt * a.T_wc[i];
    const Eigen::Isometry3d error = est[i].inverse() * a.T_wc[i];
    position += error.translation().squaredNorm();
    angle += std::pow(rotationAngleDeg(error.linear()), 2);
  }
  a.position_rmse = std::sqrt(position / est.size());
  a.rotation_rmse_deg = std::sqrt(angle / est.size());
  return a;
}

// The offset in [-30, 30] ms (0.5 ms steps) with the smallest keyframe rotation error;
// `recorded` (offset 0) unless another is smaller.
AlignedGroundTruth fitClockOffset(const Trajectory& gt, const Trajectory& keyframes,
                                  const AlignedGroundTruth& recorded) {
  AlignedGroundTruth best = recorded;
  for (int step = -60; step <= 60; ++step) {
    if (step == 0) continue;
    try {
      AlignedGroundTruth a = alignGroundTruth(gt, keyframes, step * 0.0005);
      if (a.rotation_rmse_deg < best.rotation_rmse_deg) best = std::move(a);
    } catch (const std::runtime_error&) {  // shifted past the ground truth's ends
    }
  }
  return best;
}

Json comparisonJson(const AlignedGroundTruth& a, const VoxelAgreement& r) {
  return {{"clock_offset_s", a.offset},
          {"keyframe_position_rmse_m", a.position_rmse},
          {"keyframe_rotation_rmse_deg", a.rotation_rmse_deg},
          {"occupied_estimated", r.a},
          {"occupied_ground_truth", r.b},
          {"occupied_both", r.both},
          {"strict_iou", r.iou},
          {"strict_estimated_in_ground_truth", r.a_in_b},
          {"tolerant_within_one_voxel", r.tolerant}};
}

int run(const Options& options) {
  const SystemConfig config = loadConfig(options.config);
  const TumSequence sequence(options.sequence);
  if (!sequence.hasGroundTruth())
    throw std::runtime_error(sequence.groundTruthProblem().empty()
                                 ? options.sequence + ": no groundtruth.txt"
                                 : sequence.groundTruthProblem());
  const Trajectory keyframes = readTumTrajectory(options.keyframes);
  if (keyframes.size() < 3) throw std::runtime_error(options.keyframes + ": fewer than 3 poses");

  const Trajectory& gt = sequence.groundTruth();
  const AlignedGroundTruth recorded = alignGroundTruth(gt, keyframes, options.clock_offset);
  const AlignedGroundTruth fitted =
      options.fit_clock_offset ? fitClockOffset(gt, keyframes, recorded) : recorded;

  const DenseOptions& dense = config.dense;
  const ClassPalette palette = ClassPalette::configured(dense.palette);
  const KeyFrameCloudBuilder builder(dense, palette);
  const auto octree = [&] {
    return SemanticOctree(dense.octree_resolution, dense.colour_mode, palette,
                          dense.octree_occupancy, dense.ray_margin);
  };
  // A third octree only when the fitted offset differs from the recorded stamps.
  const bool shifted = options.fit_clock_offset && fitted.offset != recorded.offset;
  SemanticOctree estimated = octree(), at_recorded = octree(), at_fitted = octree();
  for (size_t i = 0; i < keyframes.size(); ++i) {
    const RgbdImages images =
        sequence.load(frameAt(sequence, keyframes[i].stamp), config.camera.depth_factor);
    KeyFramePacket packet;
    packet.id = static_cast<long>(i);
    packet.stamp = keyframes[i].stamp;
    packet.camera = config.camera;
    packet.rgb = images.rgb;
    packet.depth = images.depth;
    packet.T_wc = keyframes[i].T_wc;
    KeyFrameCloud cloud = builder.build(packet);
    estimated.insert(cloud);
    cloud.T_wc = recorded.T_wc[i];
    at_recorded.insert(cloud);
    if (shifted) {
      cloud.T_wc = fitted.T_wc[i];
      at_fitted.insert(cloud);
    }
  }
  const auto estimated_voxels = estimated.occupiedVoxels();
  const auto compare = [&](const SemanticOctree& ground_truth) {
    return compareOccupiedVoxels(estimated_voxels, ground_truth.occupiedVoxels(),
                                 dense.octree_resolution);
  };
  const VoxelAgreement r_recorded = compare(at_recorded);
  const VoxelAgreement r = shifted ? compare(at_fitted) : r_recorded;

  Json json = {{"sequence", sequence.folder()},
               {"keyframes", keyframes.size()},
               {"octree_resolution", dense.octree_resolution},
               {"clock_offset_fitted", options.fit_clock_offset}};
  json.update(comparisonJson(fitted, r));
  if (options.fit_clock_offset) json["at_recorded_stamps"] = comparisonJson(recorded, r_recorded);
  const std::string text = json.dump(2) + "\n";
  std::cout << text;
  if (!options.out.empty()) {
    fs::create_directories(options.out);
    writeTextFileAtomically((fs::path(options.out) / "map_compare.json").string(), text);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return ply_slam::runTool("ply_slam_map_compare", kUsage, [&] { return run(parse(argc, argv)); });
}
