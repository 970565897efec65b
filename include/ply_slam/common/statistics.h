#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

namespace ply_slam {

// The one place order statistics are computed: every median and percentile of the tools and
// nodes comes from here.

// The k-th smallest of `values` (k from 0, below values.size()): a value of the sample itself.
inline double kthSmallest(std::vector<double> values, size_t k) {
  std::nth_element(values.begin(), values.begin() + k, values.end());
  return values[k];
}

// The q-quantile, q in [0, 1], interpolated linearly between the two nearest ranks (numpy's
// default): q 0 is the smallest value, 1 the largest, 0.5 the median. `values` must not be
// empty.
inline double percentile(std::vector<double> values, double q) {
  const double position = std::clamp(q, 0.0, 1.0) * static_cast<double>(values.size() - 1);
  const size_t k = static_cast<size_t>(position);
  std::nth_element(values.begin(), values.begin() + k, values.end());
  const double low = values[k];
  const double f = position - static_cast<double>(k);
  if (f == 0.0) return low;
  const double high = *std::min_element(values.begin() + k + 1, values.end());
  return (1.0 - f) * low + f * high;  // for f 0.5 exactly 0.5 * (low + high)
}

// The median: the middle value, the mean of the two middles for an even count (numpy.median, as
// TUM's scripts use). `values` must not be empty.
inline double median(const std::vector<double>& values) { return percentile(values, 0.5); }

// The same, with `if_empty` for no values (reports of runs that may have none).
inline double percentile(const std::vector<double>& values, double q, double if_empty) {
  return values.empty() ? if_empty : percentile(values, q);
}
inline double median(const std::vector<double>& values, double if_empty) {
  return values.empty() ? if_empty : median(values);
}

// The upper of the two middles for an even count: a value of the sample, for the algorithms
// that estimate from one (a shift, a noise scale). Reports use median.
inline double upperMedian(const std::vector<double>& values) {
  return kthSmallest(values, values.size() / 2);
}

}  // namespace ply_slam
