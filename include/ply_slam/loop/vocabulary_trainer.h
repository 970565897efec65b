#pragma once

#include <opencv2/core.hpp>
#include <random>
#include <string>
#include <vector>

#include "ply_slam/loop/binary_vocabulary.h"

namespace ply_slam {

// Builds a BinaryVocabulary: hierarchical k-means level by level (every node of one level is
// split before the next level starts, so progress is reported per level), then idf weights
// from the training images.
class VocabularyTrainer {
 public:
  VocabularyTrainer(const VocabularyParams& params, BinaryVocabulary::Progress progress);

  BinaryVocabulary train(const std::vector<cv::Mat>& images) const;

 private:
  struct Pending {  // a node still to be split, and the descriptors under it
    uint32_t node;
    std::vector<uint32_t> members;
  };

  // All descriptors in one contiguous buffer (rows of `bytes`).
  static std::vector<uint8_t> gather(const std::vector<cv::Mat>& images, int bytes);
  // Splits one node: appends its children to `tree`, returns those worth splitting further.
  std::vector<Pending> split(const uint8_t* data, Pending node, int child_depth,
                             VocabularyData& tree, std::mt19937_64& rng) const;
  void report(const std::string& line) const;

  VocabularyParams params_;
  BinaryVocabulary::Progress progress_;
};

}  // namespace ply_slam
