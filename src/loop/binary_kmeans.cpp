#include "ply_slam/loop/binary_kmeans.h"

#include <algorithm>
#include <climits>
#include <cstring>

#include "ply_slam/common/hamming.h"

namespace ply_slam {

namespace {

// A uniform double in [0, 1) from the engine's bits: the same on every standard library,
// unlike std::uniform_real_distribution.
double uniform01(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

}  // namespace

BinaryKMeans::BinaryKMeans(int k, int bytes, int max_iterations)
    : k_(k), bytes_(bytes), max_iterations_(max_iterations) {}

void BinaryKMeans::majority(const uint8_t* data, const std::vector<uint32_t>& members, int bytes,
                            uint8_t* centre) {
  std::vector<uint32_t> ones(static_cast<size_t>(bytes) * 8, 0);
  for (uint32_t m : members) {
    const uint8_t* d = data + static_cast<size_t>(m) * bytes;
    for (int b = 0; b < bytes; ++b)
      for (int bit = 0; bit < 8; ++bit) ones[b * 8 + bit] += (d[b] >> bit) & 1u;
  }
  for (int b = 0; b < bytes; ++b) {
    uint8_t byte = 0;
    for (int bit = 0; bit < 8; ++bit)
      if (2 * ones[b * 8 + bit] > members.size()) byte |= static_cast<uint8_t>(1u << bit);
    centre[b] = byte;
  }
}

// k-means++ (Arthur & Vassilvitskii 2007): each further seed is drawn with probability
// proportional to its squared distance to the nearest seed so far.
std::vector<uint8_t> BinaryKMeans::seed(const uint8_t* data, const std::vector<uint32_t>& members,
                                        std::mt19937_64& rng) const {
  const size_t n = members.size();
  auto row = [&](size_t i) { return data + static_cast<size_t>(members[i]) * bytes_; };
  std::vector<uint8_t> centres;
  const size_t first = rng() % n;
  centres.insert(centres.end(), row(first), row(first) + bytes_);
  std::vector<double> d2(n);
  for (size_t i = 0; i < n; ++i) {
    const double d = hammingDistance(row(i), centres.data(), bytes_);
    d2[i] = d * d;
  }
  while (static_cast<int>(centres.size() / bytes_) < k_) {
    double total = 0.0;
    for (double d : d2) total += d;
    if (total <= 0.0) break;  // every descriptor is already a seed
    double pick = uniform01(rng) * total;
    size_t chosen = 0;
    while (chosen + 1 < n && (pick -= d2[chosen]) >= 0.0) ++chosen;
    if (d2[chosen] <= 0.0) continue;  // rounding landed on a seed: draw again
    const uint8_t* c = row(chosen);
    centres.insert(centres.end(), c, c + bytes_);
    for (size_t i = 0; i < n; ++i) {
      const double d = hammingDistance(row(i), c, bytes_);
      d2[i] = std::min(d2[i], d * d);
    }
  }
  return centres;
}

int BinaryKMeans::nearest(const uint8_t* descriptor, const std::vector<uint8_t>& centres) const {
  const int n = static_cast<int>(centres.size() / bytes_);
  int best = 0, best_distance = INT_MAX;
  for (int c = 0; c < n; ++c) {
    const int d =
        hammingDistance(descriptor, centres.data() + static_cast<size_t>(c) * bytes_, bytes_);
    if (d < best_distance) {
      best_distance = d;
      best = c;
    }
  }
  return best;
}

BinaryKMeans::Result BinaryKMeans::cluster(const uint8_t* data,
                                           const std::vector<uint32_t>& members,
                                           std::mt19937_64& rng) const {
  Result result;
  if (members.empty()) return result;
  result.centres = seed(data, members, rng);
  std::vector<int> assignment(members.size(), -1);
  for (int iteration = 0; iteration < max_iterations_; ++iteration) {
    bool changed = false;
    for (size_t i = 0; i < members.size(); ++i) {
      const int c = nearest(data + static_cast<size_t>(members[i]) * bytes_, result.centres);
      changed |= c != assignment[i];
      assignment[i] = c;
    }
    const size_t n_centres = result.centres.size() / bytes_;
    result.clusters.assign(n_centres, {});
    for (size_t i = 0; i < members.size(); ++i)
      result.clusters[assignment[i]].push_back(members[i]);
    if (!changed) break;
    for (size_t c = 0; c < n_centres; ++c)
      if (!result.clusters[c].empty())
        majority(data, result.clusters[c], bytes_, result.centres.data() + c * bytes_);
  }
  // Drop empty clusters (their centre attracted nobody), keeping the order of the rest.
  std::vector<uint8_t> kept;
  std::vector<std::vector<uint32_t>> kept_clusters;
  for (size_t c = 0; c < result.clusters.size(); ++c) {
    if (result.clusters[c].empty()) continue;
    const uint8_t* centre = result.centres.data() + c * bytes_;
    kept.insert(kept.end(), centre, centre + bytes_);
    kept_clusters.push_back(std::move(result.clusters[c]));
  }
  result.centres = std::move(kept);
  result.clusters = std::move(kept_clusters);
  return result;
}

}  // namespace ply_slam
