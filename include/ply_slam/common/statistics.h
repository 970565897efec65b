#pragma once

#include <algorithm>
#include <vector>

namespace ply_slam {

// The middle value (the upper one of the two middles for an even count). `values` must not
// be empty.
inline double upperMedian(std::vector<double> values) {
  const auto mid = values.begin() + values.size() / 2;
  std::nth_element(values.begin(), mid, values.end());
  return *mid;
}

// The median (the mean of the two middles for an even count). `values` must not be empty.
inline double median(std::vector<double> values) {
  const size_t k = values.size() / 2;
  std::nth_element(values.begin(), values.begin() + k, values.end());
  if (values.size() % 2) return values[k];
  return 0.5 * (values[k] + *std::max_element(values.begin(), values.begin() + k));
}

// The same, with `if_empty` for no values (reports of runs that may have none).
inline double upperMedian(const std::vector<double>& values, double if_empty) {
  return values.empty() ? if_empty : upperMedian(values);
}
inline double median(const std::vector<double>& values, double if_empty) {
  return values.empty() ? if_empty : median(values);
}

}  // namespace ply_slam
