#include "ply_slam/loop/binary_vocabulary.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <stdexcept>

#include "ply_slam/common/hamming.h"
#include "ply_slam/loop/vocabulary_file.h"
#include "ply_slam/loop/vocabulary_trainer.h"

namespace ply_slam {

BinaryVocabulary::BinaryVocabulary(VocabularyData data) : data_(std::move(data)) { index(); }

void BinaryVocabulary::index() {
  const size_t n = data_.numNodes();
  children_.assign(n, {});
  depths_.assign(n, 0);
  for (size_t i = 1; i < n; ++i) {
    const uint32_t parent = data_.parents[i];
    if (parent >= i) throw std::runtime_error("vocabulary: a node's parent comes after it");
    children_[parent].push_back(static_cast<NodeId>(i));
    depths_[i] = depths_[parent] + 1;
  }
  word_nodes_.clear();
  node_words_.assign(n, 0);
  for (size_t i = 0; i < n; ++i) {
    if (!children_[i].empty()) continue;
    node_words_[i] = static_cast<WordId>(word_nodes_.size());
    word_nodes_.push_back(static_cast<NodeId>(i));
  }
  if (data_.idf.size() != word_nodes_.size()) data_.idf.assign(word_nodes_.size(), 0.0);
}

BinaryVocabulary BinaryVocabulary::train(const std::vector<cv::Mat>& images,
                                         const VocabularyParams& params, const Progress& progress) {
  return VocabularyTrainer(params, progress).train(images);
}

BinaryVocabulary BinaryVocabulary::load(const std::string& path, DescriptorKind expected_kind) {
  return BinaryVocabulary(VocabularyFile::read(path, expected_kind));
}

void BinaryVocabulary::save(const std::string& path) const { VocabularyFile::write(path, data_); }

WordId BinaryVocabulary::word(const uint8_t* descriptor, NodeId* node, int node_depth) const {
  NodeId current = 0;
  if (node) *node = 0;
  while (!children_[current].empty()) {
    int best_distance = INT_MAX;
    for (NodeId child : children_[current]) {
      const int d = hammingDistance(descriptor, centre(child), data_.descriptor_bytes);
      if (d < best_distance) {
        best_distance = d;
        current = child;
      }
    }
    if (node && depths_[current] <= node_depth) *node = current;
  }
  return node_words_[current];
}

void BinaryVocabulary::transform(const cv::Mat& descriptors, BowVector& bow,
                                 FeatureVector& features, int levels_up) const {
  bow.clear();
  features.clear();
  if (descriptors.empty() || empty()) return;
  CV_Assert(descriptors.type() == CV_8U && descriptors.cols == data_.descriptor_bytes);
  const int node_depth = std::max(0, data_.levels - levels_up);
  std::vector<WordId> words(descriptors.rows);
  for (int i = 0; i < descriptors.rows; ++i) {
    NodeId node;
    words[i] = word(descriptors.ptr<uint8_t>(i), &node, node_depth);
    features[node].push_back(i);
  }
  // tf-idf: the word's count in this image (its tf up to the image's size, which the L1
  // normalisation removes) times its idf.
  std::sort(words.begin(), words.end());
  for (size_t i = 0; i < words.size();) {
    size_t j = i;
    while (j < words.size() && words[j] == words[i]) ++j;
    bow.emplace_back(words[i], static_cast<double>(j - i) * data_.idf[words[i]]);
    i = j;
  }
  normaliseL1(bow);
}

BowVector BinaryVocabulary::transform(const cv::Mat& descriptors) const {
  BowVector bow;
  FeatureVector features;
  transform(descriptors, bow, features, 0);
  return bow;
}

void BinaryVocabulary::setIdf(const std::vector<cv::Mat>& images) {
  std::vector<uint32_t> images_with(numWords(), 0);
  size_t n_images = 0;
  for (const cv::Mat& d : images) {
    if (d.empty()) continue;
    ++n_images;
    std::vector<WordId> words(d.rows);
    for (int i = 0; i < d.rows; ++i) words[i] = word(d.ptr<uint8_t>(i));
    std::sort(words.begin(), words.end());
    words.erase(std::unique(words.begin(), words.end()), words.end());
    for (WordId w : words) ++images_with[w];
  }
  // A word no training image reaches by descent (k-means put its descriptors elsewhere) is
  // as rare as can be: weighted as a word of one image.
  for (size_t w = 0; w < numWords(); ++w)
    data_.idf[w] =
        n_images == 0
            ? 0.0
            : std::log(static_cast<double>(n_images) / std::max<uint32_t>(images_with[w], 1));
}

}  // namespace ply_slam
