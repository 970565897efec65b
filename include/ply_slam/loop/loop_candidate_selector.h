#pragma once

#include <set>
#include <vector>

#include "ply_slam/loop/loop_options.h"

namespace ply_slam {

// A keyframe the BoW database returned for a query, with its raw score S_fin(query, it).
struct LoopCandidate {
  long id = 0;
  double score = 0.0;
  std::vector<long> covisible;  // its covisible keyframes: with it, its consistency group
};

// One query keyframe as the selector needs it; everything comes from the caller (map, BoW
// database), so the selector depends on no vocabulary.
struct LoopQuery {
  long id = 0;
  // S_fin(query, its best covisible neighbour): the score a true revisit should reach; raw
  // scores are divided by it. <= 0: the query cannot be judged (no candidate passes).
  double reference_score = 0.0;
  std::set<long> covisible;  // keyframes already connected to the query: never loop candidates
  std::vector<LoopCandidate> candidates;
};

struct SelectedCandidate {
  long id = 0;
  double normalised_score = 0.0;
  std::set<long> group;  // the candidate and its covisible keyframes
};

// The candidates of one query that pass on their own: not the query, not covisible with it,
// normalised score score / reference_score >= options.min_normalised_score (alpha). In the
// order given.
std::vector<SelectedCandidate> scoreCandidates(const LoopQuery& query, const LoopOptions& options);

// Temporal consistency of loop candidates over consecutive queries (as ORB-SLAM's
// DetectLoop). Each passing candidate's group (it + its covisible keyframes) is compared with
// the groups kept from the previous query: sharing a keyframe with one continues that group's
// run (count + 1), sharing none starts a run at 1. A candidate is accepted when its run reaches
// options.consistency, so with 3 it is accepted on the 3rd consecutive query, not before
// (ORB-SLAM2 starts runs at 0 and so needs one query more). A query with no passing candidate
// ends every run. Only the groups of the last query are kept.
class LoopCandidateSelector {
 public:
  explicit LoopCandidateSelector(const LoopOptions& options) : options_(options) {}

  // Feed queries in keyframe order. Returns the accepted candidates, best normalised first.
  std::vector<SelectedCandidate> process(const LoopQuery& query);

  // Forget every run (e.g. after a loop was closed).
  void reset() { groups_.clear(); }

 private:
  struct Group {
    std::set<long> members;
    int count = 0;  // consecutive queries this group has been seen in
  };

  // The count this candidate's group reaches, and records its run into `next`.
  int continueRuns(const std::set<long>& group, std::vector<bool>& continued,
                   std::vector<Group>& next) const;

  LoopOptions options_;
  std::vector<Group> groups_;  // runs after the previous query
};

}  // namespace ply_slam
