#include "ply_slam/eval/trajectory_association.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>
#include <tuple>

namespace ply_slam {

std::vector<std::pair<size_t, size_t>> associateByStamp(const Trajectory& a, const Trajectory& b,
                                                        double max_dt) {
  if (!(max_dt >= 0.0)) {
    throw std::invalid_argument("associateByStamp: max_dt must be >= 0, got " +
                                std::to_string(max_dt));
  }
  // b's indices in stamp order, so each pose of a only looks at the window of b within max_dt
  // instead of at all of b (ground truth files hold thousands of poses).
  std::vector<size_t> b_by_stamp(b.size());
  std::iota(b_by_stamp.begin(), b_by_stamp.end(), size_t{0});
  std::stable_sort(b_by_stamp.begin(), b_by_stamp.end(),
                   [&b](size_t l, size_t r) { return b[l].stamp < b[r].stamp; });

  struct Candidate {
    double dt;
    size_t ia, ib;
  };
  std::vector<Candidate> candidates;
  for (size_t ia = 0; ia < a.size(); ++ia) {
    const double t = a[ia].stamp;
    if (!std::isfinite(t)) continue;
    auto it = std::lower_bound(b_by_stamp.begin(), b_by_stamp.end(), t - max_dt,
                               [&b](size_t ib, double s) { return b[ib].stamp < s; });
    for (; it != b_by_stamp.end() && b[*it].stamp <= t + max_dt; ++it) {
      const double dt = std::abs(b[*it].stamp - t);
      if (dt <= max_dt) candidates.push_back({dt, ia, *it});
    }
  }
  // Closest pairs win, as in TUM's associate.py; ties are broken by index so the result does
  // not depend on the sort implementation.
  std::sort(candidates.begin(), candidates.end(), [](const Candidate& l, const Candidate& r) {
    return std::tie(l.dt, l.ia, l.ib) < std::tie(r.dt, r.ia, r.ib);
  });

  std::vector<bool> a_used(a.size(), false), b_used(b.size(), false);
  std::vector<std::pair<size_t, size_t>> pairs;
  for (const Candidate& c : candidates) {
    if (a_used[c.ia] || b_used[c.ib]) continue;
    a_used[c.ia] = b_used[c.ib] = true;
    pairs.emplace_back(c.ia, c.ib);
  }
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

std::optional<std::pair<size_t, size_t>> findRepeatedStamp(const Trajectory& trajectory) {
  std::vector<size_t> by_stamp(trajectory.size());
  std::iota(by_stamp.begin(), by_stamp.end(), size_t{0});
  std::stable_sort(by_stamp.begin(), by_stamp.end(),
                   [&](size_t l, size_t r) { return trajectory[l].stamp < trajectory[r].stamp; });
  std::optional<std::pair<size_t, size_t>> first;
  for (size_t k = 1; k < by_stamp.size(); ++k) {
    const size_t a = by_stamp[k - 1], b = by_stamp[k];
    if (trajectory[a].stamp == trajectory[b].stamp && (!first || b < first->second))
      first = std::make_pair(a, b);
  }
  return first;
}

}  // namespace ply_slam
