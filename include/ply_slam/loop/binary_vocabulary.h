#pragma once

#include <functional>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "ply_slam/loop/bow_vector.h"
#include "ply_slam/loop/vocabulary_data.h"

namespace ply_slam {

// How a vocabulary is trained (VocabularyTrainer).
struct VocabularyParams {
  DescriptorKind kind = DescriptorKind::kOrb;
  int branching = 10;  // k
  int levels = 5;      // L
  uint64_t seed = 1;   // k-means++ seeding
  int max_iterations = 20;
};

// A hierarchical k-means vocabulary of binary words with tf-idf weights (Gálvez-López &
// Tardós 2012, "Bags of Binary Words"). A descriptor's word is found by descending from the
// root to the nearest child centre (Hamming distance) until a leaf.
class BinaryVocabulary {
 public:
  // Progress of training, one line at a time (images, descriptors, levels).
  using Progress = std::function<void(const std::string&)>;

  BinaryVocabulary() = default;
  explicit BinaryVocabulary(VocabularyData data);

  // Trains on the descriptors of each training image (rows of CV_8U, all one width).
  static BinaryVocabulary train(const std::vector<cv::Mat>& images, const VocabularyParams& params,
                                const Progress& progress = nullptr);
  // Reads a vocabulary file (VocabularyFile); throws std::runtime_error naming the file and
  // the fault, also when it holds another kind of descriptor than `expected_kind`.
  static BinaryVocabulary load(const std::string& path, DescriptorKind expected_kind);
  void save(const std::string& path) const;

  // The words of the descriptors (one per row), tf-idf weighted, unit L1 norm.
  BowVector transform(const cv::Mat& descriptors) const;
  // The same and the direct index at the nodes `levels_up` levels above the deepest words
  // (a word shallower than that stands for itself).
  void transform(const cv::Mat& descriptors, BowVector& bow, FeatureVector& features,
                 int levels_up) const;
  // The word of one descriptor; `node` (if given) gets its ancestor at depth `node_depth`.
  WordId word(const uint8_t* descriptor, NodeId* node = nullptr, int node_depth = 0) const;

  bool empty() const { return data_.numNodes() == 0; }
  DescriptorKind kind() const { return data_.kind; }
  int branching() const { return data_.branching; }
  int levels() const { return data_.levels; }
  int descriptorBytes() const { return data_.descriptor_bytes; }
  size_t numNodes() const { return data_.numNodes(); }
  size_t numWords() const { return word_nodes_.size(); }
  double idf(WordId w) const { return data_.idf[w]; }
  NodeId wordNode(WordId w) const { return word_nodes_[w]; }
  int depth(NodeId n) const { return depths_[n]; }
  // The node's centre (descriptorBytes() bytes).
  const uint8_t* centre(NodeId n) const {
    return &data_.centres[size_t{n} * data_.descriptor_bytes];
  }
  const std::vector<NodeId>& children(NodeId n) const { return children_[n]; }
  const VocabularyData& data() const { return data_; }
  // Sets the idf weights from the images' words (training does this).
  void setIdf(const std::vector<cv::Mat>& images);

 private:
  void index();  // children, depths and words from data_

  VocabularyData data_;
  std::vector<std::vector<NodeId>> children_;
  std::vector<int> depths_;
  std::vector<NodeId> word_nodes_;  // word -> node
  std::vector<WordId> node_words_;  // node -> word (leaves only)
};

}  // namespace ply_slam
