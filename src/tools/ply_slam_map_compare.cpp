// ply_slam_map_compare: how much a semantic octree built from estimated keyframe poses agrees
// with the one built from ground-truth poses, on the same images.
//   ply_slam_map_compare --sequence DIR --config FILE --keyframes KeyFrameTrajectory.txt
//                        [--out DIR]
// The ground truth (DIR/groundtruth.txt) is interpolated at the keyframe stamps and rigidly
// aligned to the estimated keyframe poses (rotations and positions: a camera that mostly turns
// in place, like fr1/rpy, leaves a positions-only alignment's rotation undetermined); both
// octrees use the config's dense section (no segmentation: meant for static sequences).
// Prints and writes DIR/map_compare.json.
// Exit codes: 0 ok, 1 bad data, 2 usage error.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "ply_slam/common/config.h"
#include "ply_slam/dense/key_frame_cloud_builder.h"
#include "ply_slam/dense/semantic_octree.h"
#include "ply_slam/dense/voxel_agreement.h"
#include "ply_slam/eval/pose_interpolation.h"
#include "ply_slam/io/tum_sequence.h"
#include "ply_slam/io/tum_trajectory_file.h"

namespace fs = std::filesystem;
using namespace ply_slam;

namespace {

struct Options {
  std::string sequence, config, keyframes, out;
};

[[noreturn]] void usage(const std::string& error) {
  std::cerr << "ply_slam_map_compare: " << error << "\n"
            << "usage: ply_slam_map_compare --sequence DIR --config FILE --keyframes FILE"
               " [--out DIR]\n";
  std::exit(2);
}

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (i + 1 >= argc) usage("missing value after " + arg);
    const std::string value = argv[++i];
    if (arg == "--sequence")
      o.sequence = value;
    else if (arg == "--config")
      o.config = value;
    else if (arg == "--keyframes")
      o.keyframes = value;
    else if (arg == "--out")
      o.out = value;
    else
      usage("unknown option " + arg);
  }
  if (o.sequence.empty() || o.config.empty() || o.keyframes.empty())
    usage("--sequence, --config and --keyframes are required");
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
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(sum, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d d = Eigen::Matrix3d::Identity();
  d(2, 2) = (svd.matrixU() * svd.matrixV().transpose()).determinant() < 0 ? -1.0 : 1.0;
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = svd.matrixU() * d * svd.matrixV().transpose();
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

int run(const Options& options) {
  const SystemConfig config = loadConfig(options.config);
  const TumSequence sequence(options.sequence);
  if (!sequence.hasGroundTruth())
    throw std::runtime_error(options.sequence + ": no groundtruth.txt");
  const Trajectory keyframes = readTumTrajectory(options.keyframes);
  if (keyframes.size() < 3) throw std::runtime_error(options.keyframes + ": fewer than 3 poses");

  std::vector<Eigen::Isometry3d> gt_poses, est_poses;
  for (const auto& k : keyframes) {
    gt_poses.push_back(interpolate(sequence.groundTruth(), k.stamp));
    est_poses.push_back(k.T_wc);
  }
  const Eigen::Isometry3d T_est_gt = alignPoses(est_poses, gt_poses);

  const DenseParams& dense = config.dense;
  const ClassPalette palette =
      dense.palette.empty() ? ClassPalette() : ClassPalette::fromFile(dense.palette);
  const KeyFrameCloudBuilder builder(dense, palette);
  const auto mode = SemanticOctree::parseColourMode(dense.colour_mode);
  SemanticOctree estimated(dense.octree_resolution, mode, palette, dense.octree_occupancy);
  SemanticOctree ground_truth(dense.octree_resolution, mode, palette, dense.octree_occupancy);
  double position_error_sum = 0.0, angle_error_sum = 0.0;
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
    cloud.T_wc = T_est_gt * gt_poses[i];
    ground_truth.insert(cloud);
    const Eigen::Isometry3d error = keyframes[i].T_wc.inverse() * cloud.T_wc;
    position_error_sum += error.translation().squaredNorm();
    angle_error_sum += std::pow(Eigen::AngleAxisd(error.linear()).angle() * 180.0 / M_PI, 2);
  }
  const VoxelAgreement r = compareOccupiedVoxels(
      estimated.occupiedVoxels(), ground_truth.occupiedVoxels(), dense.octree_resolution);
  const double keyframe_rmse = std::sqrt(position_error_sum / keyframes.size());
  const double keyframe_rmse_deg = std::sqrt(angle_error_sum / keyframes.size());

  std::ostringstream json;
  json << std::setprecision(6) << "{\n  \"sequence\": \"" << sequence.folder()
       << "\",\n  \"keyframes\": " << keyframes.size()
       << ",\n  \"keyframe_position_rmse_m\": " << keyframe_rmse
       << ",\n  \"keyframe_rotation_rmse_deg\": " << keyframe_rmse_deg
       << ",\n  \"octree_resolution\": " << dense.octree_resolution
       << ",\n  \"occupied_estimated\": " << r.a << ",\n  \"occupied_ground_truth\": " << r.b
       << ",\n  \"occupied_both\": " << r.both << ",\n  \"strict_iou\": " << r.iou
       << ",\n  \"strict_estimated_in_ground_truth\": " << r.a_in_b
       << ",\n  \"tolerant_within_one_voxel\": " << r.tolerant << "\n}\n";
  std::cout << json.str();
  if (!options.out.empty()) {
    fs::create_directories(options.out);
    std::ofstream(fs::path(options.out) / "map_compare.json") << json.str();
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const Options options = parse(argc, argv);
  try {
    return run(options);
  } catch (const std::exception& e) {
    std::cerr << "ply_slam_map_compare: " << e.what() << "\n";
    return 1;
  }
}
