#pragma once

#include <cstdint>
#include <random>
#include <vector>

namespace ply_slam {

// k-means over binary descriptors in Hamming space: k-means++ seeding, then assignment and
// k-majority centres (each bit the majority vote of the members' bits) until no descriptor
// changes cluster. Deterministic for a given random engine state.
class BinaryKMeans {
 public:
  struct Result {
    std::vector<uint8_t> centres;                 // clusters.size() x bytes
    std::vector<std::vector<uint32_t>> clusters;  // member indices, none empty
  };

  BinaryKMeans(int k, int bytes, int max_iterations = 20);

  // Clusters the descriptors data[i * bytes ...] for i in `members`. Fewer than k clusters
  // come back when there are fewer distinct descriptors.
  Result cluster(const uint8_t* data, const std::vector<uint32_t>& members,
                 std::mt19937_64& rng) const;

  // The bitwise majority of the members' descriptors (ties give 0).
  static void majority(const uint8_t* data, const std::vector<uint32_t>& members, int bytes,
                       uint8_t* centre);

 private:
  std::vector<uint8_t> seed(const uint8_t* data, const std::vector<uint32_t>& members,
                            std::mt19937_64& rng) const;
  // Index of the nearest of the n centres.
  int nearest(const uint8_t* descriptor, const std::vector<uint8_t>& centres) const;

  int k_;
  int bytes_;
  int max_iterations_;
};

}  // namespace ply_slam
