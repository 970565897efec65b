#include "ply_slam/loop/loop_candidate_selector.h"

#include <algorithm>
#include <utility>

namespace ply_slam {
namespace {

bool shareAny(const std::set<long>& a, const std::set<long>& b) {
  for (long id : a) {
    if (b.count(id)) return true;
  }
  return false;
}

}  // namespace

std::vector<SelectedCandidate> scoreCandidates(const LoopQuery& query, const LoopOptions& options) {
  std::vector<SelectedCandidate> passing;
  if (!(query.reference_score > 0.0)) return passing;
  for (const LoopCandidate& c : query.candidates) {
    if (c.id == query.id || query.covisible.count(c.id)) continue;
    const double normalised = c.score / query.reference_score;
    if (normalised < options.min_normalised_score) continue;
    SelectedCandidate selected{c.id, normalised, {c.covisible.begin(), c.covisible.end()}};
    selected.group.insert(c.id);
    passing.push_back(std::move(selected));
  }
  return passing;
}

int LoopCandidateSelector::continueRuns(const std::set<long>& group, std::vector<bool>& continued,
                                        std::vector<Group>& next) const {
  int best = 0;
  for (size_t k = 0; k < groups_.size(); ++k) {
    if (!shareAny(group, groups_[k].members)) continue;
    const int count = groups_[k].count + 1;
    // A previous group continues once, with the first candidate that reaches it (ORB-SLAM).
    if (!continued[k]) {
      next.push_back({group, count});
      continued[k] = true;
    }
    best = std::max(best, count);
  }
  if (best == 0) {
    next.push_back({group, 1});
    best = 1;
  }
  return best;
}

std::vector<SelectedCandidate> LoopCandidateSelector::process(const LoopQuery& query) {
  const std::vector<SelectedCandidate> passing = scoreCandidates(query, options_);
  std::vector<Group> next;
  std::vector<bool> continued(groups_.size(), false);
  std::vector<SelectedCandidate> accepted;
  for (const SelectedCandidate& c : passing) {
    if (continueRuns(c.group, continued, next) >= options_.consistency) accepted.push_back(c);
  }
  groups_ = std::move(next);
  std::stable_sort(accepted.begin(), accepted.end(), [](const auto& a, const auto& b) {
    return a.normalised_score > b.normalised_score;
  });
  return accepted;
}

}  // namespace ply_slam
