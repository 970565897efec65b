#pragma once

#include <functional>
#include <unordered_map>
#include <vector>

#include "ply_slam/loop/bow_vector.h"

namespace ply_slam {

// What the database keeps of one keyframe: its point (ORB) and line (LBD) bags of words and
// direct indexes.
struct KeyFrameWords {
  BowVector points, lines;
  FeatureVector point_features, line_features;
};

// A keyframe that shares at least one word with the query, with the L1 scores (bowScore) of
// its point and line bags against the query's.
struct BowCandidate {
  long keyframe_id = -1;
  double point_score = 0.0;  // S_p
  double line_score = 0.0;   // S_l
};

// Keyframes' bags of words with inverted indexes (word -> keyframes holding it, with their
// weights), one for points and one for lines, so a query touches only keyframes that share a
// word with it instead of scoring every keyframe.
class BowDatabase {
 public:
  using Exclude = std::function<bool(long keyframe_id)>;

  // The vocabularies' word counts (BinaryVocabulary::numWords()).
  BowDatabase(size_t point_words, size_t line_words);

  // Adds or replaces a keyframe. The bags are stored at unit L1 norm. Throws
  // std::out_of_range (and changes nothing) for a word beyond the vocabularies.
  void add(long keyframe_id, KeyFrameWords words);
  void remove(long keyframe_id);
  const KeyFrameWords* find(long keyframe_id) const;
  size_t size() const { return keyframes_.size(); }

  // The keyframes sharing a word with the query (points or lines), except those `exclude`
  // accepts, best first by S_p + S_l; at most max_results of them (0 = all).
  std::vector<BowCandidate> query(const BowVector& points, const BowVector& lines,
                                  size_t max_results, const Exclude& exclude = nullptr) const;
  // Relocalisation: the keyframes sharing a point word with an image's bag, most similar (S_p)
  // first, at most max_results of them; none excluded.
  std::vector<long> rankByPoints(const BowVector& points, size_t max_results) const;

 private:
  struct Posting {
    long keyframe_id;
    double weight;
  };
  using InvertedIndex = std::vector<std::vector<Posting>>;  // word -> keyframes

  // Throws std::out_of_range for a word the index does not have.
  static void check(const InvertedIndex& inverted, const BowVector& bow);
  static void index(InvertedIndex& inverted, long keyframe_id, const BowVector& bow);
  static void unindex(InvertedIndex& inverted, long keyframe_id, const BowVector& bow);
  // Adds each keyframe's score against `bow` (at unit norm) into scores[keyframe].
  static void accumulate(const InvertedIndex& inverted, const BowVector& bow, bool lines,
                         std::unordered_map<long, BowCandidate>& scores);

  InvertedIndex point_index_, line_index_;
  std::unordered_map<long, KeyFrameWords> keyframes_;
};

}  // namespace ply_slam
