#include "ply_slam/loop/vocabulary_trainer.h"

#include <algorithm>
#include <cstring>
#include <numeric>
#include <random>
#include <sstream>
#include <stdexcept>

#include "ply_slam/common/stopwatch.h"
#include "ply_slam/loop/binary_kmeans.h"

namespace ply_slam {

VocabularyTrainer::VocabularyTrainer(const VocabularyParams& params,
                                     BinaryVocabulary::Progress progress)
    : params_(params), progress_(std::move(progress)) {
  if (params_.branching < 2 || params_.levels < 1)
    throw std::invalid_argument("vocabulary: needs k >= 2 and L >= 1");
}

void VocabularyTrainer::report(const std::string& line) const {
  if (progress_) progress_(line);
}

std::vector<uint8_t> VocabularyTrainer::gather(const std::vector<cv::Mat>& images, int bytes) {
  std::vector<uint8_t> data;
  for (const cv::Mat& d : images) {
    if (d.empty()) continue;
    if (d.type() != CV_8U || d.cols != bytes)
      throw std::invalid_argument("vocabulary: descriptors must be CV_8U rows of one width");
    for (int r = 0; r < d.rows; ++r)
      data.insert(data.end(), d.ptr<uint8_t>(r), d.ptr<uint8_t>(r) + bytes);
  }
  return data;
}

std::vector<VocabularyTrainer::Pending> VocabularyTrainer::split(const uint8_t* data, Pending node,
                                                                 int child_depth,
                                                                 VocabularyData& tree,
                                                                 std::mt19937_64& rng) const {
  const int bytes = tree.descriptor_bytes;
  const BinaryKMeans kmeans(params_.branching, bytes, params_.max_iterations);
  BinaryKMeans::Result result = kmeans.cluster(data, node.members, rng);
  std::vector<Pending> further;
  if (result.clusters.size() < 2) return further;  // all alike: the node stays a leaf
  for (size_t c = 0; c < result.clusters.size(); ++c) {
    const uint32_t id = static_cast<uint32_t>(tree.parents.size());
    tree.parents.push_back(node.node);
    const uint8_t* centre = result.centres.data() + c * bytes;
    tree.centres.insert(tree.centres.end(), centre, centre + bytes);
    if (child_depth < params_.levels && result.clusters[c].size() > 1)
      further.push_back({id, std::move(result.clusters[c])});
  }
  return further;
}

BinaryVocabulary VocabularyTrainer::train(const std::vector<cv::Mat>& images) const {
  int bytes = 32;
  for (const cv::Mat& d : images)
    if (!d.empty()) bytes = d.cols;
  const std::vector<uint8_t> data = gather(images, bytes);
  const size_t n = data.size() / bytes;
  std::ostringstream line;
  line << "training on " << n << " descriptors of " << images.size() << " images, k "
       << params_.branching << ", L " << params_.levels;
  report(line.str());
  // Fewer than k descriptors make a vocabulary of one word or none: every image alike, and
  // a loop detector that uses it finds nothing without a word (issue #53).
  if (n < static_cast<size_t>(params_.branching))
    throw std::invalid_argument(
        "vocabulary: " + std::to_string(n) + " descriptors in " + std::to_string(images.size()) +
        " images, fewer than k = " + std::to_string(params_.branching) + ": nothing to train on");

  VocabularyData tree;
  tree.kind = params_.kind;
  tree.branching = params_.branching;
  tree.levels = params_.levels;
  tree.descriptor_bytes = bytes;
  tree.parents.push_back(VocabularyData::kNoParent);
  tree.centres.assign(bytes, 0);
  std::mt19937_64 rng(params_.seed);
  std::vector<Pending> level(1, Pending{0, std::vector<uint32_t>(n)});
  std::iota(level[0].members.begin(), level[0].members.end(), 0u);
  if (n < 2) level.clear();
  for (int depth = 1; depth <= params_.levels && !level.empty(); ++depth) {
    Stopwatch watch;
    std::vector<Pending> next;
    const size_t nodes_before = tree.numNodes();
    for (Pending& node : level) {
      std::vector<Pending> children = split(data.data(), std::move(node), depth, tree, rng);
      std::move(children.begin(), children.end(), std::back_inserter(next));
    }
    std::ostringstream out;
    out << "level " << depth << ": split " << level.size() << " nodes into "
        << tree.numNodes() - nodes_before << " (" << watch.elapsedMs() / 1000.0 << " s)";
    report(out.str());
    level = std::move(next);
  }
  BinaryVocabulary vocabulary(std::move(tree));
  Stopwatch watch;
  vocabulary.setIdf(images);
  std::ostringstream out;
  out << vocabulary.numNodes() << " nodes, " << vocabulary.numWords() << " words; idf in "
      << watch.elapsedMs() / 1000.0 << " s";
  report(out.str());
  return vocabulary;
}

}  // namespace ply_slam
