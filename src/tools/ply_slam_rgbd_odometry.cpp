// Baseline for side-by-side benchmarks: OpenCV contrib's dense RgbdOdometry (Steinbruecker
// et al., "Real-Time Visual Odometry from Dense RGB-D Images") run frame to frame on a TUM
// folder, with default parameters and only the camera matrix taken from our config.
//
//   ply_slam_rgbd_odometry --sequence DIR --config FILE --out TRAJ.txt [--timing-json F]

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <nlohmann/json.hpp>
#include <numeric>
#include <opencv2/core/eigen.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/rgbd/depth.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "ply_slam/common/command_line.h"
#include "ply_slam/common/se3_params.h"
#include "ply_slam/common/statistics.h"
#include "ply_slam/io/atomic_file.h"
#include "ply_slam/io/run_arguments.h"
#include "ply_slam/io/tum_sequence.h"
#include "ply_slam/io/tum_trajectory_file.h"
#include "ply_slam/system/system_config.h"

namespace {

struct Options : ply_slam::RunArguments {
  std::string timing_json;
};

const char* const kUsage =
    "usage: ply_slam_rgbd_odometry --sequence DIR --config FILE --out TRAJ.txt"
    " [--timing-json FILE]\n"
    "Runs OpenCV rgbd::RgbdOdometry (default parameters) frame to frame on a TUM folder\n"
    "and writes the chained camera poses as a TUM trajectory.\n";

Options parseOptions(int argc, char** argv) {
  Options options;
  ply_slam::CommandLine line;
  line.usage_text = kUsage;
  line.options = {"--sequence", "--config", "--out", "--timing-json"};
  line.on_option = [&](const std::string& arg, const std::string& value) {
    if (!options.take(arg, value)) options.timing_json = value;
  };
  line.parse(argc, argv);
  try {
    options.require();
  } catch (const std::invalid_argument& e) {
    throw ply_slam::UsageError(e.what());
  }
  return options;
}

// The ground-truth pose nearest in time to `stamp`: starts the estimate in the gt frame so
// the trajectory can be looked at next to it without alignment (ATE aligns anyway).
Eigen::Isometry3d nearestPose(const ply_slam::Trajectory& trajectory, double stamp) {
  auto best =
      std::min_element(trajectory.begin(), trajectory.end(),
                       [stamp](const ply_slam::StampedPose& a, const ply_slam::StampedPose& b) {
                         return std::abs(a.stamp - stamp) < std::abs(b.stamp - stamp);
                       });
  return best == trajectory.end() ? Eigen::Isometry3d::Identity() : best->T_wc;
}

// What a run of the odometry gives.
struct OdometryRun {
  ply_slam::Trajectory trajectory;
  std::vector<double> compute_ms;  // per frame after the first
  int failures = 0;
};

// The module marks missing depth with NaN, not 0.
cv::Mat odometryDepth(const cv::Mat& depth_m) {
  cv::Mat depth = depth_m.clone();
  depth.setTo(std::numeric_limits<float>::quiet_NaN(), depth == 0.0f);
  return depth;
}

// compute(src = current, dst = previous): p_previous = Rt * p_current, so Rt is
// T_previous_current and poses chain on the right.
Eigen::Isometry3d chainedStep(const cv::Mat& Rt) {
  Eigen::Matrix4d T_prev_cur;
  cv::cv2eigen(Rt, T_prev_cur);
  return ply_slam::nearestRigid(Eigen::Isometry3d(T_prev_cur));
}

// Frame to frame over the whole sequence. Only the camera matrix is set; everything else stays
// at the module's defaults. Lens distortion is ignored: the dense method works on raw pixels.
OdometryRun runOdometry(const ply_slam::TumSequence& sequence,
                        const ply_slam::PinholeCamera& camera) {
  const cv::Mat K =
      (cv::Mat_<double>(3, 3) << camera.fx, 0, camera.cx, 0, camera.fy, camera.cy, 0, 0, 1);
  const cv::Ptr<cv::rgbd::RgbdOdometry> odometry = cv::rgbd::RgbdOdometry::create(K);
  OdometryRun run;
  run.trajectory.reserve(sequence.size());
  cv::Ptr<cv::rgbd::OdometryFrame> previous;
  Eigen::Isometry3d T_wc = Eigen::Isometry3d::Identity();
  for (size_t i = 0; i < sequence.size(); ++i) {
    const ply_slam::RgbdImages images = sequence.load(i, camera.depth_factor);
    cv::Mat gray;
    cv::cvtColor(images.rgb, gray, cv::COLOR_BGR2GRAY);
    cv::Ptr<cv::rgbd::OdometryFrame> current =
        cv::rgbd::OdometryFrame::create(gray, odometryDepth(images.depth));
    if (!previous) {
      if (sequence.hasGroundTruth()) T_wc = nearestPose(sequence.groundTruth(), images.stamp);
    } else {
      cv::Mat Rt;
      // Each frame's pyramids are cached in its OdometryFrame and built once, so the
      // timing is the real per-frame cost of the method, not twice it.
      const auto start = std::chrono::steady_clock::now();
      const bool ok = odometry->compute(current, previous, Rt);
      const auto stop = std::chrono::steady_clock::now();
      run.compute_ms.push_back(std::chrono::duration<double, std::milli>(stop - start).count());
      if (ok)
        T_wc = T_wc * chainedStep(Rt);
      else
        ++run.failures;  // keep the last pose: a constant-position guess
    }
    previous = current;
    ply_slam::StampedPose pose;
    pose.stamp = images.stamp;
    pose.T_wc = T_wc;
    run.trajectory.push_back(pose);
  }
  return run;
}

void createParentFolder(const std::string& file) {
  const std::filesystem::path path(file);
  if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path());
}

// Same key names as ply_slam_tum's summary.json so scripts read both alike.
void writeTimingJson(const std::string& file, const OdometryRun& run, double median_ms,
                     double mean_ms) {
  createParentFolder(file);
  ply_slam::AtomicFile out(file);
  const nlohmann::ordered_json json = {{"method", "opencv_rgbd_odometry"},
                                       {"frames", run.trajectory.size()},
                                       {"failures", run.failures},
                                       {"tracking_ms_median", median_ms},
                                       {"tracking_ms_mean", mean_ms}};
  out.stream() << json.dump(2) << "\n";
  out.commit();
}

int run(const Options& options) {
  const ply_slam::SystemConfig config = ply_slam::loadConfig(options.config);
  const ply_slam::TumSequence sequence(options.sequence);
  if (sequence.unassociatedRgbFrames() > 0) {
    std::cerr << "note: " << sequence.unassociatedRgbFrames()
              << " rgb frames have no depth image and are skipped\n";
  }
  const OdometryRun result = runOdometry(sequence, config.camera);
  createParentFolder(options.out);
  ply_slam::writeTumTrajectory(options.out, result.trajectory);

  const std::vector<double>& ms = result.compute_ms;
  const double median_ms = ply_slam::median(ms, 0.0);
  const double mean_ms =
      ms.empty() ? 0.0
                 : std::accumulate(ms.begin(), ms.end(), 0.0) / static_cast<double>(ms.size());
  std::printf("RgbdOdometry: %zu frames, %d failed, odometry %.2f ms median, %.2f ms mean\n",
              result.trajectory.size(), result.failures, median_ms, mean_ms);
  std::printf("trajectory: %s\n", options.out.c_str());
  if (!options.timing_json.empty())
    writeTimingJson(options.timing_json, result, median_ms, mean_ms);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return ply_slam::runTool("ply_slam_rgbd_odometry", kUsage,
                           [&] { return run(parseOptions(argc, argv)); });
}
