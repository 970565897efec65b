#include "ply_slam/loop/loop_detector.h"

#include <algorithm>
#include <iterator>
#include <stdexcept>
#include <string>
#include <utility>

#include "ply_slam/common/stopwatch.h"
#include "ply_slam/loop/direct_index_matcher.h"
#include "ply_slam/loop/vocabulary_path.h"

namespace ply_slam {

LoopDetector::LoopDetector(BinaryVocabulary orb, BinaryVocabulary lbd, const PinholeCamera& camera,
                           const LoopOptions& options)
    : orb_(std::move(orb)),
      lbd_(std::move(lbd)),
      camera_(camera),
      options_(options),
      database_(orb_.numWords(), lbd_.numWords()),
      selector_(options) {
  if (orb_.empty() || lbd_.empty()) throw std::invalid_argument("LoopDetector: empty vocabulary");
}

LoopDetector LoopDetector::fromOptions(const PinholeCamera& camera, const LoopOptions& options) {
  return LoopDetector(
      BinaryVocabulary::load(vocabularyPath(options.orb_vocabulary, DescriptorKind::kOrb),
                             DescriptorKind::kOrb),
      BinaryVocabulary::load(vocabularyPath(options.lbd_vocabulary, DescriptorKind::kLbd),
                             DescriptorKind::kLbd),
      camera, options);
}

void LoopDetector::addKeyFrame(LoopKeyFrame keyframe) {
  const size_t n = static_cast<size_t>(keyframe.orb_descriptors.rows);
  if (keyframe.keypoints.size() != n || keyframe.depth.size() != n)
    throw std::invalid_argument("LoopDetector: keyframe " + std::to_string(keyframe.id) +
                                " needs one keypoint and one depth per ORB descriptor");
  KeyFrameWords words;
  orb_.transform(keyframe.orb_descriptors, words.points, words.point_features,
                 options_.direct_index_levels_up);
  if (!keyframe.lbd_descriptors.empty())
    lbd_.transform(keyframe.lbd_descriptors, words.lines, words.line_features,
                   options_.direct_index_levels_up);
  dropWeakLinks(keyframe.covisibility);
  Entry e;
  e.entropy = featureEntropy(words.points, words.lines);
  e.order = next_order_++;
  const long id = keyframe.id;
  e.keyframe = std::move(keyframe);
  database_.add(id, std::move(words));
  keyframes_[id] = std::move(e);
}

void LoopDetector::removeKeyFrame(long id) {
  if (keyframes_.erase(id) > 0) database_.remove(id);
}

void LoopDetector::setCovisibility(long id, std::map<long, int> covisibility) {
  auto it = keyframes_.find(id);
  if (it == keyframes_.end())
    throw std::out_of_range("LoopDetector: no keyframe " + std::to_string(id));
  dropWeakLinks(covisibility);
  it->second.keyframe.covisibility = std::move(covisibility);
}

void LoopDetector::dropWeakLinks(std::map<long, int>& covisibility) const {
  for (auto it = covisibility.begin(); it != covisibility.end();)
    it = it->second < options_.min_covisible_shared ? covisibility.erase(it) : std::next(it);
}

const LoopDetector::Entry& LoopDetector::entry(long id) const {
  auto it = keyframes_.find(id);
  if (it == keyframes_.end())
    throw std::out_of_range("LoopDetector: no keyframe " + std::to_string(id));
  return it->second;
}

VariantScores LoopDetector::pairScores(const Entry& query, const Entry& other, double s_p,
                                       double s_l, int* instance_matches) const {
  const InstanceFrame q{cv::Size(camera_.width, camera_.height), query.keyframe.instances};
  const InstanceFrame c{cv::Size(camera_.width, camera_.height), other.keyframe.instances};
  const LoopScore score = scoreLoopCandidate(s_p, s_l, query.entropy, q, c, options_);
  if (instance_matches) *instance_matches = score.instance_matches;
  return {s_p, s_l, score.point_line, score.final_score};
}

// Views of the same place a moment ago: the most similar says how similar a true revisit can
// look from here. (The one sharing the most landmarks, used before, can be a view from further
// off whose lower score lifts every candidate of this query above other queries' true ones.)
void LoopDetector::scoreReference(const Entry& query, LoopQueryScores& out) const {
  // Scored as the database scores the candidates: the query's bags normalised as query()
  // normalises them, against the stored (unit-norm) bags.
  const KeyFrameWords* words = database_.find(query.keyframe.id);
  BowVector points = words->points, lines = words->lines;
  normaliseL1(points);
  normaliseL1(lines);
  for (const auto& [id, shared] : query.keyframe.covisibility) {
    auto it = keyframes_.find(id);
    if (it == keyframes_.end() || it->second.order >= query.order) continue;
    const KeyFrameWords* other = database_.find(id);
    const VariantScores s = pairScores(query, it->second, unitBowScore(points, other->points),
                                       unitBowScore(lines, other->lines), nullptr);
    if (!out.reference_id || s.full > out.reference.full) out.reference_id = id;
    VariantScores& r = out.reference;
    r.points = std::max(r.points, s.points);
    r.lines = std::max(r.lines, s.lines);
    r.point_line = std::max(r.point_line, s.point_line);
    r.full = std::max(r.full, s.full);
  }
}

LoopQueryScores LoopDetector::score(long query_id) const {
  const Entry& query = entry(query_id);
  const KeyFrameWords* words = database_.find(query_id);
  LoopQueryScores out;
  out.query_id = query_id;
  scoreReference(query, out);
  // Later keyframes, the query itself, recent ones and covisible ones are never candidates.
  const auto exclude = [&](long id) {
    const Entry& e = entry(id);
    return e.order >= query.order ||
           query.keyframe.stamp - e.keyframe.stamp <= options_.min_candidate_age_s ||
           query.keyframe.covisibility.count(id) > 0;
  };
  for (const BowCandidate& c : database_.query(words->points, words->lines, 0, exclude)) {
    ScoredCandidate s;
    s.id = c.keyframe_id;
    s.raw =
        pairScores(query, entry(c.keyframe_id), c.point_score, c.line_score, &s.instance_matches);
    out.candidates.push_back(s);
  }
  return out;
}

LoopQuery LoopDetector::selectorQuery(const LoopQueryScores& scores) const {
  LoopQuery q;
  q.id = scores.query_id;
  q.reference_score = scores.reference.full;
  for (const auto& [id, shared] : entry(scores.query_id).keyframe.covisibility)
    q.covisible.insert(id);
  for (const ScoredCandidate& c : scores.candidates) {
    LoopCandidate candidate;
    candidate.id = c.id;
    candidate.score = c.raw.full;
    for (const auto& [id, shared] : entry(c.id).keyframe.covisibility)
      candidate.covisible.push_back(id);
    q.candidates.push_back(std::move(candidate));
  }
  return q;
}

LoopDetection LoopDetector::detect(long query_id) {
  LoopDetection d;
  Stopwatch watch;
  d.scores = score(query_id);
  d.consistent = selector_.process(selectorQuery(d.scores));
  d.score_ms = watch.elapsedMs();
  watch.restart();
  for (const SelectedCandidate& c : d.consistent) {
    GeometricCheckResult check = verify(query_id, c.id);
    d.checked.emplace_back(c.id, check);
    if (check.accepted) {
      d.loop = c.id;
      d.geometry = std::move(check);
      break;
    }
  }
  d.check_ms = watch.elapsedMs();
  return d;
}

std::vector<long> LoopDetector::recognise(const cv::Mat& orb_descriptors,
                                          size_t max_results) const {
  return database_.rankByPoints(orb_.transform(orb_descriptors), max_results);
}

std::vector<PutativeMatch> LoopDetector::putativeMatches(const Entry& query,
                                                         const Entry& candidate) const {
  const DirectIndexMatcher matcher(options_.match_max_distance, options_.match_ratio);
  const KeyFrameWords* q = database_.find(query.keyframe.id);
  const KeyFrameWords* c = database_.find(candidate.keyframe.id);
  std::vector<PutativeMatch> out;
  for (const auto& [iq, ic] :
       matcher.match(q->point_features, query.keyframe.orb_descriptors, c->point_features,
                     candidate.keyframe.orb_descriptors)) {
    const double zq = query.keyframe.depth[iq], zc = candidate.keyframe.depth[ic];
    if (!(zq > 0.0) || !(zc > 0.0)) continue;  // 3D-3D RANSAC needs depth in both
    PutativeMatch m;
    m.uv_query = query.keyframe.keypoints[iq];
    m.uv_candidate = candidate.keyframe.keypoints[ic];
    m.p_query = camera_.backProject(m.uv_query, zq);
    m.p_candidate = camera_.backProject(m.uv_candidate, zc);
    out.push_back(m);
  }
  return out;
}

GeometricCheckResult LoopDetector::verify(long query_id, long candidate_id) const {
  return checkLoopGeometry(putativeMatches(entry(query_id), entry(candidate_id)), camera_,
                           options_);
}

}  // namespace ply_slam
