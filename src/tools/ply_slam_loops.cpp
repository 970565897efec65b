// Place recognition on a TUM folder (PAPER.md §3.3):
//   ply_slam_loops --sequence DIR --config FILE --out DIR [--segmenter none|masks|yolo]
//                  [--model ONNX --input WxH] [--max-frames N] [--min-gap-s 10]
//                  [--false-distance-m 0.6] [--false-angle-deg 40]
// Tracks the sequence with the SLAM system, puts every keyframe into the loop detector's
// database, defines the true loops from groundtruth.txt and writes pr.csv, pr.png (precision-
// recall over the threshold alpha for ORB only, LBD only, ORB+LBD, ORB+LBD+instances),
// pr_band.png (the same with the pairs between the true and the false bounds counting neither
// way) and summary.json (counts, areas, loops accepted after consistency and the geometric
// check, under both truths).
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <opencv2/imgproc.hpp>
#include <set>
#include <sstream>

#include "ply_slam/common/command_line.h"
#include "ply_slam/common/number_text.h"
#include "ply_slam/common/statistics.h"
#include "ply_slam/common/stopwatch.h"
#include "ply_slam/eval/loop_ground_truth.h"
#include "ply_slam/eval/pose_interpolation.h"
#include "ply_slam/eval/pr_plot.h"
#include "ply_slam/eval/trajectory_metrics.h"
#include "ply_slam/io/atomic_file.h"
#include "ply_slam/io/run_arguments.h"
#include "ply_slam/io/tum_sequence.h"
#include "ply_slam/loop/loop_detector.h"
#include "ply_slam/loop/loop_key_frame_builder.h"
#include "ply_slam/semantic/segmenter_choice.h"
#include "ply_slam/system/system.h"
#include "ply_slam/system/system_config.h"

namespace fs = std::filesystem;
using namespace ply_slam;
using Json = nlohmann::ordered_json;  // keys in the order written

namespace {

constexpr const char* kUsage =
    "usage: ply_slam_loops --sequence DIR --config FILE --out DIR [--segmenter none|masks|yolo]\n"
    "                      [--model ONNX --input WxH] [--max-frames N] [--min-gap-s S]\n"
    "                      [--false-distance-m M] [--false-angle-deg D]\n"
    "  --segmenter masks: instance masks from DIR/masks and DIR/instances.txt; yolo: YOLOv8-seg\n"
    "    (model from the config's segmentation section or --model/--input)\n"
    "  --min-gap-s: true loops are keyframes more than this many seconds apart (default 10);\n"
    "    the detector's loop.min_candidate_age_s is set to it\n"
    "  true loops: within 0.3 m and 20 deg, views overlapping; --false-distance-m /\n"
    "    --false-angle-deg: false beyond these (default 0.6 m, 40 deg) or without overlap; the\n"
    "    pairs between count neither way in the curves and counts 'with_band'\n"
    "  --keep-long-links: keep the map's covisibility links between keyframes more than\n"
    "    --min-gap-s apart (default: dropped, as if tracking had not reconnected them; a\n"
    "    drift-free tracker in a small room links every keyframe to every other, and covisible\n"
    "    keyframes are never loop candidates)\n"
    "  vocabularies: the config's loop.orb_vocabulary / loop.lbd_vocabulary (\"\": the defaults\n"
    "    scripts/setup.sh trains into build/vocabulary/)\n";

struct Options : RunArguments {
  SegmenterChoice segmentation;
  long max_frames = -1;
  bool keep_long_links = false;
  LoopGroundTruthParams truth;
};

void setOption(Options& o, const std::string& arg, const std::string& value) {
  if (o.segmentation.take(arg, value) || o.take(arg, value)) return;
  if (arg == "--max-frames") {
    o.max_frames = wholeNumberArgument(arg, value, 1, 1000000000L, "a whole number >= 1");
  } else if (arg == "--min-gap-s") {
    const auto s = parseRealNumber(value);
    if (!s || *s < 0)
      throw UsageError("--min-gap-s needs a number of seconds >= 0, got '" + value + "'");
    o.truth.min_gap_s = *s;
  } else if (arg == "--false-distance-m" || arg == "--false-angle-deg") {
    const bool metres = arg == "--false-distance-m";
    const double at_least = metres ? o.truth.max_distance_m : o.truth.max_angle_deg;
    const auto x = parseRealNumber(value);
    if (!x || *x < at_least)
      throw UsageError(arg + " needs a number >= the true loops' bound " + exactText(at_least) +
                       ", got '" + value + "'");
    (metres ? o.truth.false_distance_m : o.truth.false_angle_deg) = *x;
  }
}

Options parse(int argc, char** argv) {
  Options o;
  CommandLine line;
  line.usage_text = kUsage;
  line.flags = {"--keep-long-links"};
  line.options = {
      "--sequence", "--config",     "--out",       "--segmenter",        "--model",
      "--input",    "--max-frames", "--min-gap-s", "--false-distance-m", "--false-angle-deg"};
  line.on_flag = [&](const std::string&) { o.keep_long_links = true; };
  line.on_option = [&](const std::string& arg, const std::string& value) {
    setOption(o, arg, value);
  };
  try {
    line.parse(argc, argv);
    o.segmentation.check();
    o.require();
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
  return o;
}

// The camera of a depth image downsampled by `factor` (the ground truth's overlap test).
PinholeCamera scaledCamera(const PinholeCamera& c, int factor) {
  PinholeCamera s = c;
  s.fx /= factor;
  s.fy /= factor;
  s.cx /= factor;
  s.cy /= factor;
  s.width = c.width / factor;
  s.height = c.height / factor;
  return s;
}

constexpr int kDepthFactor = 2;  // ground-truth depth kept at half size: 0.3 MB per keyframe

// Tracks the sequence and fills the detector; keeps what the ground truth needs.
class KeyFrameCollector {
 public:
  KeyFrameCollector(const SystemConfig& config, LoopDetector& detector)
      : detector_(detector),
        builder_(config.lines, config.camera, config.loop, config.dynamic.mask_dilation_px) {}

  void add(const KeyFramePacket& packet) {
    Stopwatch watch;
    cv::Mat movers;
    LoopKeyFrame kf = builder_.build(packet, &movers);
    line_counts_.push_back(kf.lbd_descriptors.rows);
    instance_counts_.push_back(static_cast<long>(kf.instances.size()));
    detector_.addKeyFrame(std::move(kf));
    add_ms_.push_back(watch.elapsedMs());
    GroundTruthView view;
    view.id = packet.id;
    view.stamp = packet.stamp;
    cv::resize(packet.depth, view.depth, cv::Size(), 1.0 / kDepthFactor, 1.0 / kDepthFactor,
               cv::INTER_NEAREST);
    if (!movers.empty())
      cv::resize(movers, view.movers, view.depth.size(), 0.0, 0.0, cv::INTER_NEAREST);
    views_.push_back(std::move(view));
  }

  std::vector<GroundTruthView>& views() { return views_; }
  const std::vector<double>& addMs() const { return add_ms_; }
  double meanLines() const { return mean(line_counts_); }
  double meanInstances() const { return mean(instance_counts_); }

 private:
  static double mean(const std::vector<long>& v) {
    double sum = 0.0;
    for (long x : v) sum += x;
    return v.empty() ? 0.0 : sum / v.size();
  }

  LoopDetector& detector_;
  LoopKeyFrameBuilder builder_;
  std::vector<GroundTruthView> views_;
  std::vector<double> add_ms_;
  std::vector<long> line_counts_, instance_counts_;
};

// Covisibility as the map has it at the end (later keyframes add links to earlier ones), without
// links between keyframes more than max_link_s apart.
void copyCovisibility(const Map& map, double max_link_s, LoopDetector& detector) {
  for (const auto& keyframe : map.keyFrames()) {
    if (!keyframe) continue;
    std::map<long, int> covisibility;
    for (const auto& [other, shared] : keyframe->covisibility)
      if (other && std::abs(other->stamp - keyframe->stamp) <= max_link_s)
        covisibility[other->id] = shared;
    try {
      detector.setCovisibility(keyframe->id, std::move(covisibility));
    } catch (const std::out_of_range&) {
      // A keyframe the detector never got (none today): nothing to update.
    }
  }
}

struct TruthTable {
  std::set<std::pair<long, long>> pairs;      // (query, earlier keyframe)
  std::set<std::pair<long, long>> dont_care;  // pairs in the band that counts neither way
  std::set<long> queries;                     // keyframes with at least one true loop
  long views_with_pose = 0;

  LoopTruth of(long query, long candidate) const {
    if (pairs.count({query, candidate})) return LoopTruth::kTrue;
    return dont_care.count({query, candidate}) ? LoopTruth::kDontCare : LoopTruth::kFalse;
  }
};

TruthTable trueLoops(std::vector<GroundTruthView>& views, const TumSequence& sequence,
                     const PinholeCamera& camera, const LoopDetector& detector,
                     const LoopGroundTruthParams& params) {
  TruthTable t;
  std::vector<bool> posed(views.size(), false);
  for (size_t i = 0; i < views.size(); ++i) {
    const auto pose = interpolatePose(sequence.groundTruth(), views[i].stamp, 0.1);
    if (!pose) continue;
    views[i].T_wc = *pose;
    posed[i] = true;
    ++t.views_with_pose;
  }
  const PinholeCamera small = scaledCamera(camera, kDepthFactor);
  for (size_t q = 0; q < views.size(); ++q) {
    if (!posed[q]) continue;
    // Keyframes tracking already connected are no loop to find (the detector never offers them).
    const std::map<long, int>& covisible = detector.keyFrame(views[q].id).covisibility;
    for (size_t c = 0; c < q; ++c) {
      if (!posed[c] || covisible.count(views[c].id)) continue;
      const LoopTruth truth = loopTruth(views[q], views[c], small, params);
      if (truth == LoopTruth::kDontCare) t.dont_care.insert({views[q].id, views[c].id});
      if (truth != LoopTruth::kTrue) continue;
      t.pairs.insert({views[q].id, views[c].id});
      t.queries.insert(views[q].id);
    }
  }
  return t;
}

}  // namespace

namespace {

// The ways of recognising a place the curves compare (LoopDetector's VariantScores).
struct Variant {
  const char* name;
  double VariantScores::*score;
};
const Variant kVariants[] = {{"orb", &VariantScores::points},
                             {"lbd", &VariantScores::lines},
                             {"orb+lbd", &VariantScores::point_line},
                             {"orb+lbd+instances", &VariantScores::full}};
constexpr size_t kNumVariants = sizeof(kVariants) / sizeof(kVariants[0]);

struct Best {
  long id = -1;
  double normalised = 0.0;
};

// The query's best candidate under one variant, its score divided by the reference's (the
// best covisible neighbour's, as alpha is applied); none when the query cannot be judged.
std::optional<Best> bestNormalised(const LoopQueryScores& s, double VariantScores::*score) {
  if (!s.reference_id || !(s.reference.*score > 0.0)) return std::nullopt;
  std::optional<Best> best;
  for (const ScoredCandidate& c : s.candidates) {
    const double n = c.raw.*score / s.reference.*score;
    if (n > 0.0 && (!best || n > best->normalised)) best = Best{c.id, n};
  }
  return best;
}

struct AcceptedLoop {
  long query = 0, candidate = 0;
  int inliers_3d = 0, reprojection_inliers = 0;
  LoopTruth truth = LoopTruth::kFalse;  // as defined (time, distance, angle, overlap)
  // Ground truth of the pair: camera distance and angle, and how far the check's estimated
  // motion is from the true one (what a loop correction would get wrong).
  double gt_distance_m = 0.0, gt_angle_deg = 0.0, motion_error_m = 0.0, motion_error_deg = 0.0;
  double query_stamp = 0.0, candidate_stamp = 0.0;
  double overlap = 0.0;  // the larger of the two views' overlaps (the definition's test)
};

AcceptedLoop acceptedLoop(const GroundTruthView& query, const GroundTruthView& candidate,
                          const GeometricCheckResult& check, const TruthTable& truth,
                          const PinholeCamera& small, const LoopGroundTruthParams& params) {
  AcceptedLoop a;
  a.query = query.id;
  a.candidate = candidate.id;
  a.query_stamp = query.stamp;
  a.candidate_stamp = candidate.stamp;
  a.overlap = std::max(viewOverlap(query, candidate, small, params),
                       viewOverlap(candidate, query, small, params));
  a.inliers_3d = check.inliers_3d;
  a.reprojection_inliers = check.reprojection_inliers;
  a.truth = truth.of(query.id, candidate.id);
  const Eigen::Isometry3d T_qc = query.T_wc.inverse() * candidate.T_wc;  // ground truth
  a.gt_distance_m = T_qc.translation().norm();
  a.gt_angle_deg = rotationAngleDeg(T_qc.linear());
  const Eigen::Isometry3d error = T_qc.inverse() * check.T_query_candidate;
  a.motion_error_m = error.translation().norm();
  a.motion_error_deg = rotationAngleDeg(error.linear());
  return a;
}

// One query's decision under one variant, with the pair's ground truth (decisions.csv).
struct DecisionRow {
  long query = 0, candidate = 0;
  size_t variant = 0;
  double normalised = 0.0, gt_distance_m = 0.0, gt_angle_deg = 0.0;
  LoopTruth truth = LoopTruth::kFalse;
  bool query_has_loop = false;
};

// One candidate of one query: its raw scores, the query's reference scores and the pair's
// ground truth (candidates.csv: every selection rule can be judged from it).
struct CandidateRow {
  long query = 0, reference = -1, candidate = 0;
  VariantScores reference_scores, raw;
  int instance_matches = 0;
  double gt_distance_m = 0.0, gt_angle_deg = 0.0;
  LoopTruth truth = LoopTruth::kFalse;
  bool query_has_loop = false;
};

// What the detector did over the whole sequence.
struct LoopRun {
  std::vector<DecisionRow> rows;  // the curves' decisions
  std::vector<CandidateRow> candidate_rows;
  std::vector<AcceptedLoop> accepted;
  long geometry_checked = 0, geometry_passed_true = 0, geometry_passed_dont_care = 0,
       geometry_passed_false = 0;
  long judged = 0, candidates = 0, covisible = 0;  // queries with a reference; sums over queries
  std::vector<double> score_ms, check_ms;
};

void recordCandidates(const GroundTruthView& query, const LoopQueryScores& scores,
                      const std::map<long, const GroundTruthView*>& by_id, const TruthTable& truth,
                      std::vector<CandidateRow>& rows) {
  for (const ScoredCandidate& c : scores.candidates) {
    CandidateRow row;
    row.query = query.id;
    row.reference = scores.reference_id.value_or(-1);
    row.reference_scores = scores.reference;
    row.candidate = c.id;
    row.raw = c.raw;
    row.instance_matches = c.instance_matches;
    const Eigen::Isometry3d T_qc = query.T_wc.inverse() * by_id.at(c.id)->T_wc;
    row.gt_distance_m = T_qc.translation().norm();
    row.gt_angle_deg = rotationAngleDeg(T_qc.linear());
    row.truth = truth.of(query.id, c.id);
    row.query_has_loop = truth.queries.count(query.id) > 0;
    rows.push_back(row);
  }
}

// Every keyframe in order as a query: the curves' decisions, the loops accepted after alpha,
// consistency and the geometric check, and the geometric check alone on each query's best
// ORB+LBD+instances candidate (what it would have to stop at any alpha).
LoopRun runQueries(LoopDetector& detector, const std::vector<GroundTruthView>& views,
                   const TruthTable& truth, const PinholeCamera& small,
                   const LoopGroundTruthParams& params) {
  LoopRun run;
  std::map<long, const GroundTruthView*> by_id;
  for (const GroundTruthView& view : views) by_id[view.id] = &view;
  for (const GroundTruthView& view : views) {
    const LoopDetection d = detector.detect(view.id);
    run.score_ms.push_back(d.score_ms);
    run.check_ms.push_back(d.check_ms);
    run.judged += d.scores.reference_id.has_value();
    run.candidates += static_cast<long>(d.scores.candidates.size());
    run.covisible += static_cast<long>(detector.keyFrame(view.id).covisibility.size());
    recordCandidates(view, d.scores, by_id, truth, run.candidate_rows);
    for (size_t v = 0; v < kNumVariants; ++v) {
      const std::optional<Best> best = bestNormalised(d.scores, kVariants[v].score);
      if (!best) continue;
      const Eigen::Isometry3d T_qc = view.T_wc.inverse() * by_id.at(best->id)->T_wc;
      run.rows.push_back({view.id, best->id, v, best->normalised, T_qc.translation().norm(),
                          rotationAngleDeg(T_qc.linear()), truth.of(view.id, best->id),
                          truth.queries.count(view.id) > 0});
    }
    if (d.loop)
      run.accepted.push_back(
          acceptedLoop(view, *by_id.at(*d.loop), *d.geometry, truth, small, params));
    const std::optional<Best> best = bestNormalised(d.scores, &VariantScores::full);
    if (!best) continue;
    ++run.geometry_checked;
    if (!detector.verify(view.id, best->id).accepted) continue;
    const LoopTruth judged = truth.of(view.id, best->id);
    (judged == LoopTruth::kTrue       ? run.geometry_passed_true
     : judged == LoopTruth::kDontCare ? run.geometry_passed_dont_care
                                      : run.geometry_passed_false)++;
  }
  return run;
}

// The two ways a decision is judged: by the definition (true or not), or with the band
// between the true and the false bounds counting neither way (its decisions left out).
enum class Judged { kByDefinition, kWithBand };

// One variant's decisions, as the precision-recall curve takes them.
std::vector<ScoredDecision> decisionsOf(const std::vector<DecisionRow>& rows, size_t variant,
                                        Judged judged) {
  std::vector<ScoredDecision> out;
  for (const DecisionRow& r : rows)
    if (r.variant == variant &&
        (judged == Judged::kByDefinition || r.truth != LoopTruth::kDontCare))
      out.push_back({r.normalised, r.truth == LoopTruth::kTrue});
  return out;
}

const char* truthWord(LoopTruth t) {
  return t == LoopTruth::kTrue ? "true" : t == LoopTruth::kDontCare ? "dont_care" : "false";
}

void writeDecisions(const fs::path& out, const std::vector<DecisionRow>& rows) {
  AtomicFile file((out / "decisions.csv").string());
  std::ostream& csv = file.stream();
  csv << "query,variant,candidate,normalised_score,truth,query_has_true_loop,gt_distance_m,"
         "gt_angle_deg\n"
      << std::setprecision(6);
  for (const DecisionRow& r : rows)
    csv << r.query << ',' << kVariants[r.variant].name << ',' << r.candidate << ',' << r.normalised
        << ',' << truthWord(r.truth) << ',' << r.query_has_loop << ',' << r.gt_distance_m << ','
        << r.gt_angle_deg << '\n';
  file.commit();
}

void writeCandidates(const fs::path& out, const std::vector<CandidateRow>& rows) {
  AtomicFile file((out / "candidates.csv").string());
  std::ostream& csv = file.stream();
  csv << "query,reference,candidate,ref_orb,ref_lbd,ref_orb_lbd,ref_full,orb,lbd,orb_lbd,full,"
         "instance_matches,truth,query_has_true_loop,gt_distance_m,gt_angle_deg\n"
      << std::setprecision(6);
  for (const CandidateRow& r : rows) {
    const VariantScores& f = r.reference_scores;
    csv << r.query << ',' << r.reference << ',' << r.candidate << ',' << f.points << ',' << f.lines
        << ',' << f.point_line << ',' << f.full << ',' << r.raw.points << ',' << r.raw.lines << ','
        << r.raw.point_line << ',' << r.raw.full << ',' << r.instance_matches << ','
        << truthWord(r.truth) << ',' << r.query_has_loop << ',' << r.gt_distance_m << ','
        << r.gt_angle_deg << '\n';
  }
  file.commit();
}

// An accepted loop whose estimated motion is this close to the ground truth's (m, deg) would
// correct the map rightly even where the pair misses the true-loop definition.
constexpr double kMotionTolerance_m = 0.1, kMotionTolerance_deg = 2.0;

struct RunInfo {
  long frames = 0, lost = 0, keyframes = 0;
  double vocabulary_load_ms = 0.0, mean_lines = 0.0, mean_instances = 0.0;
  std::vector<double> add_ms;
};

// One curve's figures in summary.json (NaN: null).
Json curveJson(const PrCurve& c) {
  return {{"auc", c.average_precision},
          {"recall_at_precision_1", c.recall_at_full_precision},
          {"alpha_at_precision_1", c.threshold_at_full_precision},
          {"decisions", c.points.empty() ? 0 : c.points.back().detections}};
}

// Each variant's curve by the definition and with the band counting neither way.
using Curves = std::vector<std::pair<std::string, PrCurve>>;
struct BothCurves {
  Curves by_definition, with_band;
};

BothCurves curvesOf(const LoopRun& run, const TruthTable& truth) {
  BothCurves c;
  const auto positives = static_cast<long>(truth.queries.size());
  for (size_t v = 0; v < kNumVariants; ++v) {
    c.by_definition.emplace_back(
        kVariants[v].name,
        precisionRecall(decisionsOf(run.rows, v, Judged::kByDefinition), positives));
    c.with_band.emplace_back(
        std::string(kVariants[v].name) + ", band",
        precisionRecall(decisionsOf(run.rows, v, Judged::kWithBand), positives));
  }
  return c;
}

// pr.csv (both truths, column `truth`), pr.png (by the definition) and pr_band.png.
void writeCurves(const fs::path& out, const BothCurves& curves, const std::string& title) {
  AtomicFile csv_file((out / "pr.csv").string());
  std::ostream& csv = csv_file.stream();
  csv << "variant,truth,threshold,detections,true_positives,precision,recall\n"
      << std::setprecision(6);
  for (const auto& [truth, list] :
       {std::pair{"by_definition", &curves.by_definition}, {"with_band", &curves.with_band}})
    for (size_t v = 0; v < list->size(); ++v)
      for (const PrPoint& p : (*list)[v].second.points)
        csv << kVariants[v].name << ',' << truth << ',' << p.threshold << ',' << p.detections << ','
            << p.true_positives << ',' << p.precision << ',' << p.recall << '\n';
  csv_file.commit();
  writePrPlot((out / "pr.png").string(), curves.by_definition, title);
  writePrPlot((out / "pr_band.png").string(), curves.with_band,
              title + ", the band counting neither way");
}

Json truthJson(const LoopGroundTruthParams& t, const TruthTable& truth) {
  return {{"min_gap_s", t.min_gap_s},
          {"max_distance_m", t.max_distance_m},
          {"max_angle_deg", t.max_angle_deg},
          {"min_overlap", t.min_overlap},
          {"false_distance_m", t.false_distance_m},
          {"false_angle_deg", t.false_angle_deg},
          {"keyframes_with_ground_truth", truth.views_with_pose},
          {"pairs", truth.pairs.size()},
          {"dont_care_pairs", truth.dont_care.size()},
          {"queries", truth.queries.size()}};
}

Json loopJson(const AcceptedLoop& a) {
  return {{"query", a.query},
          {"candidate", a.candidate},
          {"inliers_3d", a.inliers_3d},
          {"reprojection_inliers", a.reprojection_inliers},
          {"truth", truthWord(a.truth)},
          {"gt_distance_m", a.gt_distance_m},
          {"gt_angle_deg", a.gt_angle_deg},
          {"motion_error_m", a.motion_error_m},
          {"motion_error_deg", a.motion_error_deg},
          {"stamps", {a.query_stamp, a.candidate_stamp}},
          {"overlap", a.overlap}};
}

Json acceptedJson(const LoopRun& run, double alpha) {
  long correct = 0, dont_care = 0, consistent = 0;
  double worst_m = 0.0, worst_deg = 0.0;
  Json loops = Json::array();
  for (const AcceptedLoop& a : run.accepted) {
    correct += a.truth == LoopTruth::kTrue;
    dont_care += a.truth == LoopTruth::kDontCare;
    consistent +=
        a.motion_error_m <= kMotionTolerance_m && a.motion_error_deg <= kMotionTolerance_deg;
    worst_m = std::max(worst_m, a.motion_error_m);
    worst_deg = std::max(worst_deg, a.motion_error_deg);
    loops.push_back(loopJson(a));
  }
  const long count = static_cast<long>(run.accepted.size());
  return {{"alpha", alpha},
          {"count", count},
          {"correct", correct},
          {"dont_care", dont_care},
          {"false", count - correct - dont_care},
          {"precision", count == 0 ? 1.0 : double(correct) / count},
          {"precision_with_band", count == dont_care ? 1.0 : double(correct) / (count - dont_care)},
          {"motion_within_tolerance", consistent},
          {"motion_tolerance", {kMotionTolerance_m, kMotionTolerance_deg}},
          {"max_motion_error_m", worst_m},
          {"max_motion_error_deg", worst_deg},
          {"loops", loops}};
}

Json timingJson(const RunInfo& info, const LoopRun& run) {
  return {{"vocabulary_load", info.vocabulary_load_ms},
          {"add_keyframe_median", median(info.add_ms, 0.0)},
          {"query_median", median(run.score_ms, 0.0)},
          {"query_max", percentile(run.score_ms, 1.0, 0.0)},
          {"geometric_check_median", median(run.check_ms, 0.0)},
          {"geometric_check_max", percentile(run.check_ms, 1.0, 0.0)}};
}

void writeSummary(const fs::path& out, const Options& o, const RunInfo& info,
                  const TruthTable& truth, const LoopRun& run, const BothCurves& curves,
                  double alpha) {
  const double keyframes = static_cast<double>(std::max<long>(1, info.keyframes));
  Json variants = Json::object();
  for (size_t v = 0; v < curves.by_definition.size(); ++v)
    variants[curves.by_definition[v].first] = {
        {"by_definition", curveJson(curves.by_definition[v].second)},
        {"with_band", curveJson(curves.with_band[v].second)}};
  const Json json = {{"sequence", o.sequence},
                     {"config", o.config},
                     {"segmenter", o.segmentation.kind},
                     {"frames", info.frames},
                     {"lost_frames", info.lost},
                     {"keyframes", info.keyframes},
                     {"mean_lines_per_keyframe", info.mean_lines},
                     {"mean_instances_per_keyframe", info.mean_instances},
                     {"true_loops", truthJson(o.truth, truth)},
                     {"queries",
                      {{"judged", run.judged},
                       {"mean_candidates", run.candidates / keyframes},
                       {"mean_covisible", run.covisible / keyframes}}},
                     {"variants", variants},
                     {"accepted_loops", acceptedJson(run, alpha)},
                     {"geometry_on_best_candidates",
                      {{"checked", run.geometry_checked},
                       {"passed_true", run.geometry_passed_true},
                       {"passed_dont_care", run.geometry_passed_dont_care},
                       {"passed_false", run.geometry_passed_false}}},
                     {"timing_ms", timingJson(info, run)}};
  AtomicFile file((out / "summary.json").string());
  file.stream() << json.dump(2) << "\n";
  file.commit();
}

LoopDetector makeDetector(const SystemConfig& config, double min_gap_s, RunInfo& info) {
  // Candidates as old as true loops must be: none is left out that could be one.
  LoopOptions options = config.loop;
  options.min_candidate_age_s = min_gap_s;
  Stopwatch watch;
  LoopDetector detector = LoopDetector::fromOptions(config.camera, options);
  info.vocabulary_load_ms = watch.elapsedMs();
  return detector;
}

// Tracks every frame; each new keyframe goes to the collector.
void track(const Options& o, const SystemConfig& config, const TumSequence& sequence,
           KeyFrameCollector& collector, System& system, RunInfo& info) {
  std::unique_ptr<Segmenter> segmenter =
      o.segmentation.make(config.segmentation, sequence.folder());
  const size_t n =
      o.max_frames > 0 ? std::min<size_t>(sequence.size(), o.max_frames) : sequence.size();
  for (size_t i = 0; i < n; ++i) {
    const RgbdImages images = sequence.load(i, config.camera.depth_factor);
    const std::vector<Instance> instances =
        segmenter ? segmenter->segment(images) : std::vector<Instance>{};
    const FrameResult r = system.process(images, instances);
    ++info.frames;
    info.lost += r.tracking.state != TrackingState::kOk;
    for (const MappedKeyFrame& mapped : r.mapped)
      if (mapped.packet) collector.add(*mapped.packet);
  }
}

int run(const Options& o) {
  SystemConfig config = loadConfig(o.config);
  // The system under the evaluation only tracks: its own loop closure would move the map and
  // link the very keyframes whose recognition is measured.
  config.loop.enabled = false;
  // Every keyframe tracking makes is a query: a culled one would leave the map's covisibility,
  // which names each query's reference and the keyframes it must not take for a loop.
  config.culling.keyframes.redundancy = 1.0;
  if (o.segmentation.kind == "none")
    config.dynamic.mode = modeWithoutSegmenter(config.dynamic.mode);
  const TumSequence sequence(o.sequence);
  if (!sequence.hasGroundTruth())
    throw std::runtime_error((sequence.groundTruthProblem().empty()
                                  ? o.sequence + ": no groundtruth.txt"
                                  : sequence.groundTruthProblem()) +
                             ", true loops cannot be defined");
  fs::create_directories(o.out);
  RunInfo info;
  LoopDetector detector = makeDetector(config, o.truth.min_gap_s, info);
  KeyFrameCollector collector(config, detector);
  System system(config);
  track(o, config, sequence, collector, system, info);
  info.keyframes = static_cast<long>(collector.views().size());
  info.add_ms = collector.addMs();
  info.mean_lines = collector.meanLines();
  info.mean_instances = collector.meanInstances();
  copyCovisibility(system.map(),
                   o.keep_long_links ? std::numeric_limits<double>::infinity() : o.truth.min_gap_s,
                   detector);
  const TruthTable truth = trueLoops(collector.views(), sequence, config.camera, detector, o.truth);
  const LoopRun run = runQueries(detector, collector.views(), truth,
                                 scaledCamera(config.camera, kDepthFactor), o.truth);
  const BothCurves curves = curvesOf(run, truth);
  const std::string title = fs::path(sequence.folder()).filename().string() + "  (" +
                            std::to_string(truth.queries.size()) + " queries with a true loop)";
  writeCurves(o.out, curves, title);
  writeDecisions(o.out, run.rows);
  writeCandidates(o.out, run.candidate_rows);
  writeSummary(o.out, o, info, truth, run, curves, config.loop.min_normalised_score);
  long correct = 0, dont_care = 0;
  for (const AcceptedLoop& a : run.accepted) {
    correct += a.truth == LoopTruth::kTrue;
    dont_care += a.truth == LoopTruth::kDontCare;
  }
  std::cout << info.frames << " frames, " << info.keyframes << " keyframes, " << truth.pairs.size()
            << " true loop pairs (" << truth.queries.size() << " queries), "
            << truth.dont_care.size() << " pairs counting neither way\n";
  for (size_t v = 0; v < kNumVariants; ++v) {
    const PrCurve& strict = curves.by_definition[v].second;
    const PrCurve& band = curves.with_band[v].second;
    std::cout << "  " << std::left << std::setw(18) << kVariants[v].name << " AUC "
              << std::setprecision(3) << strict.average_precision << ", recall at precision 1 "
              << strict.recall_at_full_precision << "; with the band AUC " << band.average_precision
              << ", recall at precision 1 " << band.recall_at_full_precision << "\n";
  }
  std::cout << "accepted loops " << run.accepted.size() << " (" << correct << " true, " << dont_care
            << " in the band); outputs in " << fs::absolute(o.out).string() << "\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return ply_slam::runTool("ply_slam_loops", kUsage, [&] { return run(parse(argc, argv)); });
}
