// Line features on a TUM RGB-D folder, both 3D methods side by side:
//   ply_slam_lines --sequence DIR --config FILE [--max-frames N] [--offset K] [--json]
// Reports, for the paper's sampled fit (PAPER.md §3.1) and the "traditional" endpoint
// back-projection on the same 2D segments:
//   - the mean line reconstruction rate N_3D / N_2D over frames;
//   - the accuracy of the accepted 3D segments: each one of frame k is moved into frame k+K
//     (default 5) by the ground-truth relative pose, projected, and its endpoints' distances
//     to the observed segment it matches there are collected (median px). The match is made
//     by LBD descriptors alone (mutual nearest, ratio test), so it does not depend on either
//     3D fit and both methods are judged on the same correspondences;
//   - the median ms per frame of extraction, description and fitting.
// Ground truth in TUM is T_wc of the rgb optical centre, interpolated at each rgb stamp.
//
// Exit codes: 0 ok, 1 unreadable data or config, 2 usage error.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iomanip>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <opencv2/imgproc.hpp>

#include "ply_slam/common/command_line.h"
#include "ply_slam/common/statistics.h"
#include "ply_slam/common/stopwatch.h"
#include "ply_slam/eval/pose_interpolation.h"
#include "ply_slam/features/frame_lines.h"
#include "ply_slam/features/line_distance.h"
#include "ply_slam/features/line_extractor.h"
#include "ply_slam/features/line_fitter.h"
#include "ply_slam/features/line_matcher.h"
#include "ply_slam/io/tum_sequence.h"
#include "ply_slam/system/system_config.h"

using namespace ply_slam;
using Json = nlohmann::ordered_json;  // keys in the order written

namespace {

struct Options {
  std::string sequence, config;
  long max_frames = -1;
  int offset = 5;
  bool json = false;
};

const char* const kUsage =
    "usage: ply_slam_lines --sequence DIR --config FILE [--max-frames N] [--offset K] [--json]\n";

long parsePositive(const std::string& option, const std::string& text) {
  return wholeNumberArgument(option, text, 1, 1000000000L, "a whole number >= 1");
}

Options parse(int argc, char** argv) {
  Options o;
  CommandLine line;
  line.usage_text = kUsage;
  line.flags = {"--json"};
  line.options = {"--sequence", "--config", "--max-frames", "--offset"};
  line.on_flag = [&](const std::string&) { o.json = true; };
  line.on_option = [&](const std::string& arg, const std::string& value) {
    if (arg == "--sequence")
      o.sequence = value;
    else if (arg == "--config")
      o.config = value;
    else if (arg == "--max-frames")
      o.max_frames = parsePositive(arg, value);
    else
      o.offset = static_cast<int>(parsePositive(arg, value));
  };
  line.parse(argc, argv);
  if (o.sequence.empty() || o.config.empty())
    throw UsageError("--sequence and --config are required");
  return o;
}

double mean(const std::vector<double>& v) {
  if (v.empty()) return std::nan("");
  double sum = 0.0;
  for (double x : v) sum += x;
  return sum / v.size();
}

double fraction(const std::vector<double>& v, double limit) {
  if (v.empty()) return std::nan("");
  return static_cast<double>(
             std::count_if(v.begin(), v.end(), [&](double x) { return x <= limit; })) /
         v.size();
}

struct MethodReport {
  std::vector<double> rates, fitting_ms, distances_px;
  long accepted = 0, accepted_matched = 0;
};

std::string number(double v, int precision = 4) {
  if (!std::isfinite(v)) return "null";
  std::ostringstream out;
  out << std::setprecision(precision) << std::fixed << v;
  return out.str();
}

// NaN (no sample) is written as null.
Json methodJson(const MethodReport& r) {
  return {{"rate_mean", mean(r.rates)},
          {"accepted_lines", r.accepted},
          {"accepted_lines_matched", r.accepted_matched},
          {"endpoint_distances", r.distances_px.size()},
          {"distance_median_px", median(r.distances_px, std::nan(""))},
          {"distance_mean_px", mean(r.distances_px)},
          {"within_2px", fraction(r.distances_px, 2.0)},
          {"fitting_ms_median", median(r.fitting_ms, std::nan(""))}};
}

void printMethod(const char* name, const MethodReport& r, int offset) {
  std::cout << "  " << name << "\n"
            << "    reconstruction rate (mean N_3D/N_2D)  " << number(100.0 * mean(r.rates), 1)
            << " %\n"
            << "    accepted 3D lines                     " << r.accepted << " ("
            << r.accepted_matched << " matched in k+" << offset << ")\n"
            << "    k->k+" << offset << " endpoint-to-line distance    median "
            << number(median(r.distances_px, std::nan("")), 3) << " px, mean "
            << number(mean(r.distances_px), 3) << " px, <= 2 px "
            << number(100.0 * fraction(r.distances_px, 2.0), 1) << " % (" << r.distances_px.size()
            << " endpoints)\n"
            << "    fitting                               median "
            << number(median(r.fitting_ms, std::nan("")), 3) << " ms\n";
}

// The same 2D lines of one frame with two 3D fits, and its ground-truth pose.
struct Frame {
  FrameLines sampled, endpoints;
  std::optional<Eigen::Isometry3d> T_wc;
};

// Everything the tool reports.
struct LinesReport {
  MethodReport sampled, endpoints;
  std::vector<double> extraction_ms, description_ms, total_ms, lines_per_frame;
  size_t frames = 0;
  long pairs = 0, matches_total = 0, gated_total = 0;  // frame pairs k -> k+offset
  double perPair(long count) const {
    return pairs ? static_cast<double>(count) / pairs : std::nan("");
  }
};

// The tool's parts, built from the config.
struct LineTools {
  explicit LineTools(const SystemConfig& config)
      : camera(config.camera),
        extractor(config.lines),
        fitter(config.lines, camera),
        matcher(config.lines, camera) {}
  const PinholeCamera camera;
  const LineExtractor extractor;
  const LineFitter fitter;
  const LineMatcher matcher;
};

// One frame's lines fitted both ways, its timings and rates into the report.
Frame extractFrame(const TumSequence& sequence, size_t i, const LineTools& tools,
                   LinesReport& report) {
  const RgbdImages images = sequence.load(i, tools.camera.depth_factor);
  cv::Mat gray;
  cv::cvtColor(images.rgb, gray, cv::COLOR_BGR2GRAY);
  Frame f;
  LineTimings t;
  f.sampled = FrameLines::extract(gray, images.depth, tools.camera, tools.extractor, tools.fitter,
                                  LineFitMethod::kSampled, &t);
  f.endpoints = f.sampled;
  Stopwatch watch;
  f.endpoints.fit(images.depth, tools.fitter, LineFitMethod::kEndpoints);
  report.endpoints.fitting_ms.push_back(watch.elapsedMs());
  report.sampled.fitting_ms.push_back(t.fitting_ms);
  report.extraction_ms.push_back(t.extraction_ms);
  report.description_ms.push_back(t.description_ms);
  report.total_ms.push_back(t.extraction_ms + t.description_ms + t.fitting_ms);
  report.lines_per_frame.push_back(static_cast<double>(f.sampled.size()));
  report.sampled.rates.push_back(f.sampled.reconstructionRate());
  report.endpoints.rates.push_back(f.endpoints.reconstructionRate());
  report.sampled.accepted += static_cast<long>(f.sampled.numLines3D());
  report.endpoints.accepted += static_cast<long>(f.endpoints.numLines3D());
  if (sequence.hasGroundTruth())
    f.T_wc = interpolatePose(sequence.groundTruth(), images.stamp, 0.05);
  return f;
}

// Both fits of frame a's matched lines moved into frame b (T_ba): the distances of their
// projected endpoints from the line observed in b.
void scorePair(const Frame& a, const Frame& b, const Eigen::Isometry3d& T_ba,
               const std::vector<LineMatch>& matches, const PinholeCamera& camera,
               LinesReport& report) {
  for (const LineMatch& m : matches) {
    const Eigen::Vector3d l = b.sampled.lines[m.b].line();
    for (auto [lines, method] :
         {std::pair{&a.sampled, &report.sampled}, {&a.endpoints, &report.endpoints}}) {
      const Line3D& line = lines->lines3d[m.a];
      if (!line.valid) continue;
      const Eigen::Vector3d Ps = T_ba * line.start, Pe = T_ba * line.end;
      if (Ps.z() <= 0.0 || Pe.z() <= 0.0) continue;
      ++method->accepted_matched;
      method->distances_px.push_back(std::abs(lineDistance(l, camera.project(Ps))));
      method->distances_px.push_back(std::abs(lineDistance(l, camera.project(Pe))));
    }
  }
}

// Accuracy: frame k's accepted 3D lines in frame k+offset under the ground-truth motion.
void scoreAccuracy(const std::vector<Frame>& frames, int offset, const LineTools& tools,
                   LinesReport& report) {
  for (size_t k = 0; k + offset < frames.size(); ++k) {
    const Frame& a = frames[k];
    const Frame& b = frames[k + offset];
    if (!a.T_wc || !b.T_wc) continue;
    ++report.pairs;
    const Eigen::Isometry3d T_ba = b.T_wc->inverse() * *a.T_wc;
    const std::vector<LineMatch> matches = tools.matcher.matchDescriptors(a.sampled, b.sampled);
    report.matches_total += static_cast<long>(matches.size());
    report.gated_total +=
        static_cast<long>(tools.matcher.matchProjected(a.sampled, b.sampled, T_ba).size());
    scorePair(a, b, T_ba, matches, tools.camera, report);
  }
}

void printJson(const Options& options, const std::string& detector, const LinesReport& r) {
  const Json timing = {{"extraction_median", median(r.extraction_ms, std::nan(""))},
                       {"description_median", median(r.description_ms, std::nan(""))},
                       {"fitting_median", median(r.sampled.fitting_ms, std::nan(""))},
                       {"total_median", median(r.total_ms, std::nan(""))}};
  const Json json = {{"sequence", options.sequence},
                     {"frames", r.frames},
                     {"detector", detector},
                     {"lines_per_frame", mean(r.lines_per_frame)},
                     {"offset", options.offset},
                     {"frame_pairs", r.pairs},
                     {"descriptor_matches_per_pair", r.perPair(r.matches_total)},
                     {"gated_matches_per_pair", r.perPair(r.gated_total)},
                     {"sampled", methodJson(r.sampled)},
                     {"endpoints", methodJson(r.endpoints)},
                     {"timing_ms", timing}};
  std::cout << json.dump() << "\n";
}

void printText(const Options& options, const std::string& detector, const LinesReport& r) {
  std::cout << "Line features: " << options.sequence << "\n"
            << "  frames " << r.frames << ", detector " << detector << ", 2D lines per frame "
            << number(mean(r.lines_per_frame), 1) << "\n"
            << "  frame pairs k->k+" << options.offset << " with ground truth " << r.pairs
            << ", LBD matches per pair " << number(r.perPair(r.matches_total), 1)
            << " (pose-gated matcher with the true pose: " << number(r.perPair(r.gated_total), 1)
            << ")\n";
  printMethod("PAPER.md §3.1 (sampled, RANSAC, PCA)", r.sampled, options.offset);
  printMethod("traditional (endpoint depth)", r.endpoints, options.offset);
  std::cout << "  time per frame (median)  extraction "
            << number(median(r.extraction_ms, std::nan("")), 2) << " ms, description "
            << number(median(r.description_ms, std::nan("")), 2) << " ms, fitting "
            << number(median(r.sampled.fitting_ms, std::nan("")), 2) << " ms, total "
            << number(median(r.total_ms, std::nan("")), 2) << " ms\n";
}

int run(const Options& options) {
  const LineTools tools(loadConfig(options.config));
  const TumSequence sequence(options.sequence);
  const size_t n = options.max_frames > 0
                       ? std::min(sequence.size(), static_cast<size_t>(options.max_frames))
                       : sequence.size();
  LinesReport report;
  std::vector<Frame> frames;
  frames.reserve(n);
  for (size_t i = 0; i < n; ++i) frames.push_back(extractFrame(sequence, i, tools, report));
  report.frames = frames.size();
  scoreAccuracy(frames, options.offset, tools, report);
  if (options.json)
    printJson(options, tools.extractor.detectorName(), report);
  else
    printText(options, tools.extractor.detectorName(), report);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return ply_slam::runTool("ply_slam_lines", kUsage, [&] { return run(parse(argc, argv)); });
}
