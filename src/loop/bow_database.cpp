#include "ply_slam/loop/bow_database.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace ply_slam {

BowDatabase::BowDatabase(size_t point_words, size_t line_words)
    : point_index_(point_words), line_index_(line_words) {}

void BowDatabase::check(const InvertedIndex& inverted, const BowVector& bow) {
  for (const auto& entry : bow)
    if (entry.first >= inverted.size())
      throw std::out_of_range("BowDatabase: word " + std::to_string(entry.first) +
                              " beyond the vocabulary's " + std::to_string(inverted.size()));
}

void BowDatabase::index(InvertedIndex& inverted, long keyframe_id, const BowVector& bow) {
  for (const auto& [word, weight] : bow) inverted[word].push_back({keyframe_id, weight});
}

void BowDatabase::unindex(InvertedIndex& inverted, long keyframe_id, const BowVector& bow) {
  for (const auto& entry : bow) {
    std::vector<Posting>& list = inverted[entry.first];
    list.erase(std::remove_if(list.begin(), list.end(),
                              [&](const Posting& p) { return p.keyframe_id == keyframe_id; }),
               list.end());
  }
}

void BowDatabase::add(long keyframe_id, KeyFrameWords words) {
  check(point_index_, words.points);  // before any change: a bad bag leaves the database as it was
  check(line_index_, words.lines);
  remove(keyframe_id);
  normaliseL1(words.points);
  normaliseL1(words.lines);
  index(point_index_, keyframe_id, words.points);
  index(line_index_, keyframe_id, words.lines);
  keyframes_.emplace(keyframe_id, std::move(words));
}

void BowDatabase::remove(long keyframe_id) {
  const auto it = keyframes_.find(keyframe_id);
  if (it == keyframes_.end()) return;
  unindex(point_index_, keyframe_id, it->second.points);
  unindex(line_index_, keyframe_id, it->second.lines);
  keyframes_.erase(it);
}

const KeyFrameWords* BowDatabase::find(long keyframe_id) const {
  const auto it = keyframes_.find(keyframe_id);
  return it == keyframes_.end() ? nullptr : &it->second;
}

// unitBowScore of the (normalised) query against every keyframe at once: the query's words in
// order, each adding its sharedWordScore to the keyframes whose postings hold it.
void BowDatabase::accumulate(const InvertedIndex& inverted, const BowVector& bow, bool lines,
                             std::unordered_map<long, BowCandidate>& scores) {
  for (const auto& [word, weight] : bow) {
    if (word >= inverted.size()) continue;
    for (const Posting& p : inverted[word]) {
      BowCandidate& c = scores[p.keyframe_id];
      c.keyframe_id = p.keyframe_id;
      (lines ? c.line_score : c.point_score) += sharedWordScore(weight, p.weight);
    }
  }
}

std::vector<BowCandidate> BowDatabase::query(const BowVector& points, const BowVector& lines,
                                             size_t max_results, const Exclude& exclude) const {
  BowVector p = points, l = lines;
  normaliseL1(p);
  normaliseL1(l);
  std::unordered_map<long, BowCandidate> scores;
  scores.reserve(keyframes_.size());
  accumulate(point_index_, p, false, scores);
  accumulate(line_index_, l, true, scores);
  std::vector<BowCandidate> out;
  out.reserve(scores.size());
  for (const auto& entry : scores)
    if (!exclude || !exclude(entry.first)) out.push_back(entry.second);
  auto better = [](const BowCandidate& a, const BowCandidate& b) {
    const double sa = a.point_score + a.line_score, sb = b.point_score + b.line_score;
    return sa != sb ? sa > sb : a.keyframe_id < b.keyframe_id;  // ties: stable order
  };
  const size_t n = max_results == 0 ? out.size() : std::min(max_results, out.size());
  std::partial_sort(out.begin(), out.begin() + n, out.end(), better);
  out.resize(n);
  return out;
}

std::vector<long> BowDatabase::rankByPoints(const BowVector& points, size_t max_results) const {
  std::vector<BowCandidate> found = query(points, BowVector{}, 0);
  // query ranks by S_p + S_l; an image without lines is ranked by its points alone.
  std::stable_sort(found.begin(), found.end(), [](const BowCandidate& a, const BowCandidate& b) {
    return a.point_score > b.point_score;
  });
  std::vector<long> ids;
  for (size_t i = 0; i < found.size() && i < max_results; ++i) ids.push_back(found[i].keyframe_id);
  return ids;
}

}  // namespace ply_slam
