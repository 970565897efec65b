// ply_slam_eval: ATE and RPE of an estimated TUM trajectory against ground truth, with the
// TUM benchmark's definitions (see ply_slam/eval/trajectory_metrics.h).
//
// Exit codes: 0 success, 1 unreadable/malformed input or too little overlap, 2 usage error.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <iostream>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "ply_slam/common/angles.h"
#include "ply_slam/common/command_line.h"
#include "ply_slam/common/number_text.h"
#include "ply_slam/eval/trajectory_association.h"
#include "ply_slam/eval/trajectory_metrics.h"
#include "ply_slam/eval/trajectory_plot.h"
#include "ply_slam/io/tum_trajectory_file.h"

namespace {

using Json = nlohmann::ordered_json;  // keys in the order written

constexpr int kExitData = 1;

const char* const kUsage =
    "usage: ply_slam_eval ate GT EST [--max-dt S] [--json] [--plot PNG]\n"
    "                            [--align-with REF [--align-truth REF_GT]]\n"
    "       ply_slam_eval rpe GT EST [--delta N | --delta-seconds S] [--max-dt S] [--json]\n"
    "\n"
    "GT and EST are TUM trajectory files ('stamp tx ty tz qx qy qz qw' per line).\n"
    "  ate              absolute trajectory error after rigid (no scale) alignment\n"
    "  rpe              relative pose error over pose pairs N frames (default 1) or S seconds\n"
    "                   apart, in the estimate's order\n"
    "  --max-dt S       largest stamp difference for associating poses (default 0.02 s)\n"
    "  --json           print one JSON object instead of text\n"
    "  --plot PNG       (ate) also write a top/side view of gt and the aligned estimate\n"
    "  --align-with REF (ate) align EST with the alignment fitted to REF, an estimate in the\n"
    "                   same frame (the run that made a map EST was localised in), not its own\n"
    "  --align-truth REF_GT  the ground truth REF is aligned to, when REF is another pass of\n"
    "                   the place than GT (default GT: the same frames)\n"
    "A stamp given twice in a file, a non-finite number or coordinates too large to square\n"
    "are errors naming the file.\n"
    "Exit codes: 0 ok, 1 unreadable/malformed data or too few pairs, 2 usage error.\n";

using ply_slam::UsageError;

struct Options {
  std::string command;
  std::string gt_path, est_path;
  double max_dt = 0.02;
  bool json = false;
  std::string plot_path;
  std::string align_with;   // ate: the estimate whose fitted alignment EST is judged with
  std::string align_truth;  // and its ground truth, when not GT
  std::optional<int> delta_frames;
  std::optional<double> delta_seconds;
};

double parseNumber(const std::string& option, const std::string& text, bool allow_zero) {
  const std::optional<double> value = ply_slam::parseRealNumber(text);
  if (!value || *value < 0.0 || (!allow_zero && *value == 0.0)) {
    throw UsageError(option + " needs a " + (allow_zero ? "non-negative" : "positive") +
                     " number, got '" + text + "'");
  }
  return *value;
}

int parseFrameCount(const std::string& option, const std::string& text) {
  return static_cast<int>(
      ply_slam::wholeNumberArgument(option, text, 1, 1000000, "a whole number of frames >= 1"));
}

// The command (ate or rpe) first, then its options and the two files.
Options parseArguments(int argc, char** argv) {
  Options options;
  std::vector<std::string> positional;
  ply_slam::CommandLine line;
  line.usage_text = kUsage;
  line.flags = {"--json"};
  line.options = {"--max-dt",      "--plot",  "--align-with",
                  "--align-truth", "--delta", "--delta-seconds"};
  line.unknown_hint = [&]() -> std::string {
    return options.command.empty() ? " (the command, ate or rpe, comes first)"
                                   : " for '" + options.command + "'";
  };
  line.on_positional = [&](const std::string& arg) {
    if (!options.command.empty()) {
      positional.push_back(arg);
      return;
    }
    if (arg != "ate" && arg != "rpe")
      throw UsageError("unknown command '" + arg + "' (expected 'ate' or 'rpe')");
    options.command = arg;
  };
  // The options of the other command, and any before the command, are unknown here.
  const std::set<std::string> ate_only = {"--plot", "--align-with", "--align-truth"},
                              rpe_only = {"--delta", "--delta-seconds"};
  auto check = [&](const std::string& arg) {
    const std::set<std::string>& other = options.command == "ate" ? rpe_only : ate_only;
    if (options.command.empty() || other.count(arg))
      throw UsageError("unknown option " + arg + line.unknown_hint());
  };
  line.on_flag = [&](const std::string& arg) {
    check(arg);
    options.json = true;
  };
  line.on_option = [&](const std::string& arg, const std::string& value) {
    check(arg);
    if (arg == "--max-dt")
      options.max_dt = parseNumber(arg, value, true);
    else if (arg == "--plot")
      options.plot_path = value;
    else if (arg == "--align-with")
      options.align_with = value;
    else if (arg == "--align-truth")
      options.align_truth = value;
    else if (arg == "--delta")
      options.delta_frames = parseFrameCount(arg, value);
    else
      options.delta_seconds = parseNumber(arg, value, false);
  };
  line.parse(argc, argv);
  if (options.command.empty()) throw UsageError("missing command 'ate' or 'rpe'");
  if (!options.align_truth.empty() && options.align_with.empty())
    throw UsageError("--align-truth needs --align-with");
  if (positional.size() != 2) {
    throw UsageError("'" + options.command + "' needs exactly two files, GT and EST, got " +
                     std::to_string(positional.size()));
  }
  if (options.delta_frames && options.delta_seconds) {
    throw UsageError("--delta and --delta-seconds exclude each other");
  }
  options.gt_path = positional[0];
  options.est_path = positional[1];
  return options;
}

std::string number(double value) {
  char text[40];
  std::snprintf(text, sizeof(text), "%.10g", value);
  return text;
}

std::string fixed(double value) {
  if (std::abs(value) < 5e-7) value = 0.0;  // no "-0.000000" for rounding noise
  char text[40];
  std::snprintf(text, sizeof(text), "%.6f", value);
  return text;
}

// A stamp given twice would be paired twice (with two ground-truth poses) and count twice.
ply_slam::Trajectory readNonEmpty(const std::string& path, const char* role) {
  ply_slam::Trajectory trajectory = ply_slam::readTumTrajectory(path);
  if (trajectory.empty()) {
    throw std::runtime_error(std::string(role) + " file '" + path + "' holds no poses");
  }
  if (const auto repeated = ply_slam::findRepeatedStamp(trajectory)) {
    throw std::runtime_error(std::string(role) + " file '" + path + "' gives stamp " +
                             fixed(trajectory[repeated->second].stamp) + " twice (poses " +
                             std::to_string(repeated->first + 1) + " and " +
                             std::to_string(repeated->second + 1) + ")");
  }
  return trajectory;
}

// Coordinates near the largest double make the errors overflow to inf or NaN, which are no
// numbers to report (nor valid JSON).
void requireFinite(const ply_slam::ErrorStats& s, const char* what) {
  for (const double v : {s.rmse, s.mean, s.median, s.max})
    if (!std::isfinite(v))
      throw std::runtime_error(std::string(what) +
                               " is not a finite number: the coordinates are too large");
}

int runAte(const Options& options, const ply_slam::Trajectory& gt,
           const ply_slam::Trajectory& est) {
  // A run in a loaded map is judged in that map's frame: aligned as the run that made it.
  // The reference may be another pass of the place, with a ground truth of its own.
  const auto referenceAlignment = [&] {
    const ply_slam::Trajectory reference_gt =
        options.align_truth.empty() ? gt
                                    : readNonEmpty(options.align_truth, "reference ground truth");
    return ply_slam::computeAte(reference_gt, readNonEmpty(options.align_with, "reference"),
                                options.max_dt)
        .T_gt_est;
  };
  const ply_slam::AteResult ate =
      options.align_with.empty()
          ? ply_slam::computeAte(gt, est, options.max_dt)
          : ply_slam::computeAteInFrame(gt, est, referenceAlignment(), options.max_dt);
  const ply_slam::ErrorStats& s = ate.translation;
  requireFinite(s, "the ATE");
  // Beside it the estimate's scale against the truth (a fitted map frame has none of its own).
  std::optional<ply_slam::SimilarityAteResult> sim;
  if (options.align_with.empty()) sim = ply_slam::computeAteSimilarity(gt, est, options.max_dt);
  if (options.json) {
    Json json = {{"pairs", s.count},
                 {"rmse", s.rmse},
                 {"mean", s.mean},
                 {"median", s.median},
                 {"max", s.max}};
    if (sim) {
      json["sim3_scale"] = sim->scale;
      json["sim3_rmse"] = sim->translation.rmse;
    }
    std::cout << json.dump() << "\n";
  } else {
    const Eigen::Vector3d t = ate.T_gt_est.translation();
    const double angle_deg = ply_slam::rotationAngleDeg(ate.T_gt_est.linear());
    std::cout << "ATE (TUM, rigid alignment without scale"
              << (options.align_with.empty() ? "" : ", fitted to " + options.align_with) << ")\n"
              << "  ground truth  " << options.gt_path << " (" << gt.size() << " poses)\n"
              << "  estimate      " << options.est_path << " (" << est.size() << " poses)\n"
              << "  pairs         " << s.count << " (max_dt " << options.max_dt << " s)\n"
              << "  rmse          " << fixed(s.rmse) << " m\n"
              << "  mean          " << fixed(s.mean) << " m\n"
              << "  median        " << fixed(s.median) << " m\n"
              << "  max           " << fixed(s.max) << " m\n"
              << "  alignment     t = (" << fixed(t.x()) << ", " << fixed(t.y()) << ", "
              << fixed(t.z()) << ") m, rotation " << fixed(angle_deg) << " deg\n";
    if (sim)
      std::cout << "  with scale    rmse " << fixed(sim->translation.rmse) << " m, scale "
                << fixed(sim->scale) << " (Sim(3): > 1, the estimate is smaller)\n";
  }
  if (!options.plot_path.empty()) {
    ply_slam::Trajectory aligned = est;
    for (ply_slam::StampedPose& pose : aligned) pose.T_wc = ate.T_gt_est * pose.T_wc;
    ply_slam::writeTrajectoryPlot(options.plot_path, gt, aligned,
                                  "ATE rmse " + fixed(s.rmse) + " m: " + options.est_path);
    if (!options.json) std::cout << "  plot          " << options.plot_path << "\n";
  }
  return 0;
}

int runRpe(const Options& options, const ply_slam::Trajectory& gt,
           const ply_slam::Trajectory& est) {
  const ply_slam::RpeResult rpe =
      options.delta_seconds
          ? ply_slam::computeRpeSeconds(gt, est, *options.delta_seconds, options.max_dt)
          : ply_slam::computeRpeFrames(gt, est, options.delta_frames.value_or(1), options.max_dt);
  const ply_slam::ErrorStats& t = rpe.translation;
  const ply_slam::ErrorStats& r = rpe.rotation;
  requireFinite(t, "the RPE");
  requireFinite(r, "the RPE");
  if (options.json) {
    const Json json = {
        {"pairs", t.count},         {"trans_rmse", t.rmse},       {"trans_mean", t.mean},
        {"trans_median", t.median}, {"trans_max", t.max},         {"rot_rmse_deg", r.rmse},
        {"rot_mean_deg", r.mean},   {"rot_median_deg", r.median}, {"rot_max_deg", r.max}};
    std::cout << json.dump() << "\n";
    return 0;
  }
  const std::string delta = options.delta_seconds
                                ? number(*options.delta_seconds) + " s"
                                : std::to_string(options.delta_frames.value_or(1)) + " frame(s)";
  std::cout << "RPE (TUM) over pose pairs " << delta << " apart\n"
            << "  ground truth  " << options.gt_path << " (" << gt.size() << " poses)\n"
            << "  estimate      " << options.est_path << " (" << est.size() << " poses)\n"
            << "  pairs         " << t.count << " (max_dt " << options.max_dt << " s)\n"
            << "                translation [m]   rotation [deg]\n";
  const std::pair<const char*, double ply_slam::ErrorStats::*> rows[] = {
      {"rmse", &ply_slam::ErrorStats::rmse},
      {"mean", &ply_slam::ErrorStats::mean},
      {"median", &ply_slam::ErrorStats::median},
      {"max", &ply_slam::ErrorStats::max}};
  for (const auto& [name, field] : rows) {
    char line[96];
    std::snprintf(line, sizeof(line), "  %-12s  %15.6f   %14.6f\n", name, t.*field, r.*field);
    std::cout << line;
  }
  return 0;
}

int run(const Options& options) {
  ply_slam::Trajectory gt, est;
  try {
    gt = readNonEmpty(options.gt_path, "ground truth");
    est = readNonEmpty(options.est_path, "estimate");
  } catch (const std::exception& e) {
    std::cerr << "ply_slam_eval: " << e.what() << "\n";
    return kExitData;
  }
  try {
    return options.command == "ate" ? runAte(options, gt, est) : runRpe(options, gt, est);
  } catch (const std::exception& e) {
    // The library's messages give counts; name the files here so the user knows which run.
    std::cerr << "ply_slam_eval: " << options.command << " of '" << options.est_path
              << "' against '" << options.gt_path << "': " << e.what() << "\n";
    return kExitData;
  }
}

}  // namespace

int main(int argc, char** argv) {
  return ply_slam::runTool("ply_slam_eval", kUsage,
                           [&] { return run(parseArguments(argc, argv)); });
}
