#pragma once

#include <Eigen/Core>
#include <map>
#include <opencv2/core.hpp>
#include <optional>
#include <set>
#include <unordered_map>
#include <vector>

#include "ply_slam/common/pinhole_camera.h"
#include "ply_slam/loop/binary_vocabulary.h"
#include "ply_slam/loop/bow_database.h"
#include "ply_slam/loop/geometric_check.h"
#include "ply_slam/loop/loop_candidate_selector.h"
#include "ply_slam/loop/loop_options.h"
#include "ply_slam/loop/loop_score.h"
#include "ply_slam/semantic/instance_box.h"

namespace ply_slam {

// What loop detection keeps of one keyframe.
struct LoopKeyFrame {
  long id = 0;
  double stamp = 0.0;                      // s
  cv::Mat orb_descriptors;                 // N x 32 CV_8U
  std::vector<Eigen::Vector2d> keypoints;  // undistorted pixels, one per ORB row
  std::vector<float> depth;                // m per keypoint, 0 = none
  cv::Mat lbd_descriptors;                 // M x 32 CV_8U (may be empty: no lines)
  std::vector<InstanceBox> instances;      // the keyframe's segmented objects (any class)
  // Keyframe id -> landmarks shared with it; links below options.min_covisible_shared are
  // dropped when the detector takes the keyframe.
  std::map<long, int> covisibility;
};

// The scores of one (query, candidate) pair under each way of recognising a place that the
// precision-recall evaluation compares: ORB only (S_p), LBD only (S_l), both with entropy
// weights (S_pl) and both with instances (S_fin, PAPER.md §3.3).
struct VariantScores {
  double points = 0.0;
  double lines = 0.0;
  double point_line = 0.0;
  double full = 0.0;
};

struct ScoredCandidate {
  long id = 0;
  VariantScores raw;
  int instance_matches = 0;
};

// Every candidate of one query with raw scores, and the reference the scores are divided by:
// the same scores against the query's best covisible neighbour, the earlier covisible keyframe
// that scores highest (each variant's own best).
struct LoopQueryScores {
  long query_id = 0;
  std::optional<long> reference_id;  // the best by S_fin; none: no earlier covisible keyframe,
                                     // the query cannot be judged
  VariantScores reference;
  // Keyframes sharing a word with the query, added before it, at least
  // options.min_candidate_age_s older and not covisible with it.
  std::vector<ScoredCandidate> candidates;
};

// What one detect() found.
struct LoopDetection {
  LoopQueryScores scores;
  std::vector<SelectedCandidate> consistent;  // passed alpha and the 3-query consistency
  std::vector<std::pair<long, GeometricCheckResult>> checked;  // geometric checks run
  std::optional<long> loop;                                    // the accepted candidate
  std::optional<GeometricCheckResult> geometry;                // its check (T_query_candidate)
  double score_ms = 0.0, check_ms = 0.0;
};

// Place recognition of PAPER.md §3.3 over a growing set of keyframes: both vocabularies, the
// point + line BoW database, the scores, candidate selection and the geometric check. It sees
// keyframes only through LoopKeyFrame, so it runs beside the tracker and mapper, not in them.
// A query considers only keyframes added before it (what a running system would have).
class LoopDetector {
 public:
  LoopDetector(BinaryVocabulary orb, BinaryVocabulary lbd, const PinholeCamera& camera,
               const LoopOptions& options);

  // Loads the vocabularies the options name (vocabularyPath: "" = the defaults); throws
  // std::runtime_error naming a missing or bad file.
  static LoopDetector fromOptions(const PinholeCamera& camera, const LoopOptions& options);

  // Adds (or replaces) a keyframe. Throws std::invalid_argument when the keypoints or depths do
  // not match the ORB rows.
  void addKeyFrame(LoopKeyFrame keyframe);
  // Forgets a keyframe (culled from the map): it is no candidate of any later query, nor
  // a reference. Unknown ids are ignored.
  void removeKeyFrame(long id);
  // Covisibility grows as later keyframes see the same landmarks: replace it.
  void setCovisibility(long id, std::map<long, int> covisibility);
  size_t size() const { return keyframes_.size(); }
  // Throws std::out_of_range for an id never added.
  const LoopKeyFrame& keyFrame(long id) const { return entry(id).keyframe; }

  // Raw scores of the query against the earlier, old enough, non-covisible keyframes.
  LoopQueryScores score(long query_id) const;
  // score(), then alpha, the consistency over consecutive queries (call in keyframe order) and
  // the geometric check of the consistent candidates, best first, until one passes.
  LoopDetection detect(long query_id);
  // Relocalisation: the keyframes whose ORB words an image's descriptors share, most similar
  // (S_p) first, at most max_results; no keyframe is excluded.
  std::vector<long> recognise(const cv::Mat& orb_descriptors, size_t max_results) const;
  // The geometric check of one pair (direct-index ORB matches with depth in both).
  GeometricCheckResult verify(long query_id, long candidate_id) const;

  const LoopOptions& options() const { return options_; }
  const BinaryVocabulary& orbVocabulary() const { return orb_; }
  const BinaryVocabulary& lbdVocabulary() const { return lbd_; }

 private:
  struct Entry {
    LoopKeyFrame keyframe;
    size_t order = 0;  // insertion index: candidates must come before the query
    FeatureEntropy entropy;
  };

  const Entry& entry(long id) const;
  void dropWeakLinks(std::map<long, int>& covisibility) const;
  VariantScores pairScores(const Entry& query, const Entry& other, double s_p, double s_l,
                           int* instance_matches) const;
  // reference_id and reference of `out`: the query against its earlier covisible keyframes.
  void scoreReference(const Entry& query, LoopQueryScores& out) const;
  LoopQuery selectorQuery(const LoopQueryScores& scores) const;
  std::vector<PutativeMatch> putativeMatches(const Entry& query, const Entry& candidate) const;

  BinaryVocabulary orb_, lbd_;
  PinholeCamera camera_;
  LoopOptions options_;
  BowDatabase database_;
  LoopCandidateSelector selector_;
  std::unordered_map<long, Entry> keyframes_;
  size_t next_order_ = 0;
};

}  // namespace ply_slam
