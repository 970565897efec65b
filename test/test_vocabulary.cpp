// The binary vocabulary (module loop): hierarchical k-means on known clusters, tf-idf, the
// L1 score, and the vocabulary file with its checks.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <map>
#include <stdexcept>

#include "loop_test_data.h"
#include "ply_slam/common/hamming.h"
#include "ply_slam/loop/binary_vocabulary.h"

namespace ply_slam {
namespace {

constexpr int kClusters = 8;

// Images of descriptors drawn around 8 random centres (up to 6 bits flipped each): image i
// holds 30 descriptors of cluster i % 8 and 30 of cluster 0.
struct ClusterData {
  cv::Mat centres;
  std::vector<cv::Mat> images;
  std::vector<std::vector<int>> labels;  // per image, the true cluster of each row
};

ClusterData makeClusters(int n_images = 16) {
  std::mt19937 rng(42);
  ClusterData data;
  data.centres = test::randomDescriptors(kClusters, rng);
  for (int i = 0; i < n_images; ++i) {
    cv::Mat image;
    std::vector<int> labels;
    for (int cluster : {i % kClusters, 0})
      for (int j = 0; j < 30; ++j) {
        image.push_back(test::flipBits(data.centres.row(cluster), 1 + rng() % 6, rng));
        labels.push_back(cluster);
      }
    data.images.push_back(image);
    data.labels.push_back(labels);
  }
  return data;
}

VocabularyParams params(int k, int levels, DescriptorKind kind = DescriptorKind::kOrb) {
  VocabularyParams p;
  p.kind = kind;
  p.branching = k;
  p.levels = levels;
  p.seed = 7;
  return p;
}

TEST(Vocabulary, KMeansRecoversKnownClusters) {
  const ClusterData data = makeClusters();
  const BinaryVocabulary vocabulary = BinaryVocabulary::train(data.images, params(kClusters, 1));
  ASSERT_EQ(vocabulary.numWords(), static_cast<size_t>(kClusters));
  std::map<int, WordId> word_of_cluster;
  for (size_t i = 0; i < data.images.size(); ++i)
    for (int r = 0; r < data.images[i].rows; ++r) {
      const WordId w = vocabulary.word(data.images[i].ptr<uint8_t>(r));
      const int cluster = data.labels[i][r];
      const auto [it, inserted] = word_of_cluster.emplace(cluster, w);
      EXPECT_EQ(it->second, w) << "cluster " << cluster << " split over two words";
    }
  std::set<WordId> distinct;
  for (const auto& [cluster, w] : word_of_cluster) {
    distinct.insert(w);
    // The k-majority centre is the true centre: the flips are too few to outvote it.
    EXPECT_EQ(hammingDistance(vocabulary.centre(vocabulary.wordNode(w)),
                              data.centres.ptr<uint8_t>(cluster), 32),
              0)
        << "cluster " << cluster;
  }
  EXPECT_EQ(distinct.size(), static_cast<size_t>(kClusters)) << "two clusters share a word";
}

TEST(Vocabulary, DeeperTreeKeepsEachWordInOneCluster) {
  const ClusterData data = makeClusters();
  const BinaryVocabulary vocabulary = BinaryVocabulary::train(data.images, params(3, 4));
  EXPECT_GT(vocabulary.numWords(), static_cast<size_t>(kClusters));
  std::map<WordId, int> cluster_of_word;
  for (size_t i = 0; i < data.images.size(); ++i)
    for (int r = 0; r < data.images[i].rows; ++r) {
      const auto [it, inserted] = cluster_of_word.emplace(
          vocabulary.word(data.images[i].ptr<uint8_t>(r)), data.labels[i][r]);
      EXPECT_EQ(it->second, data.labels[i][r]) << "word " << it->first << " mixes clusters";
    }
  for (size_t w = 0; w < vocabulary.numWords(); ++w)
    EXPECT_LE(vocabulary.depth(vocabulary.wordNode(static_cast<WordId>(w))), 4);
}

TEST(Vocabulary, TrainingIsDeterministicForASeed) {
  const ClusterData data = makeClusters();
  const BinaryVocabulary a = BinaryVocabulary::train(data.images, params(3, 3));
  const BinaryVocabulary b = BinaryVocabulary::train(data.images, params(3, 3));
  EXPECT_EQ(a.data().parents, b.data().parents);
  EXPECT_EQ(a.data().centres, b.data().centres);
  EXPECT_EQ(a.data().idf, b.data().idf);
}

TEST(Vocabulary, IdfIsLogOfImagesOverImagesWithTheWord) {
  const ClusterData data = makeClusters();  // 16 images; cluster 0 in all, others in 2 each
  const BinaryVocabulary vocabulary = BinaryVocabulary::train(data.images, params(kClusters, 1));
  for (int cluster = 0; cluster < kClusters; ++cluster) {
    const WordId w = vocabulary.word(data.centres.ptr<uint8_t>(cluster));
    EXPECT_NEAR(vocabulary.idf(w), cluster == 0 ? 0.0 : std::log(16.0 / 2.0), 1e-12);
  }
}

TEST(Vocabulary, TransformWeighsByTfIdfAtUnitNorm) {
  const ClusterData data = makeClusters();
  const BinaryVocabulary vocabulary = BinaryVocabulary::train(data.images, params(kClusters, 1));
  // 3 descriptors of cluster 1, 1 of cluster 2: weights 3 idf : 1 idf (equal idf), sum 1.
  cv::Mat query;
  for (int cluster : {1, 1, 1, 2}) query.push_back(data.centres.row(cluster));
  BowVector bow;
  FeatureVector features;
  vocabulary.transform(query, bow, features, 0);
  ASSERT_EQ(bow.size(), 2u);
  const WordId w1 = vocabulary.word(data.centres.ptr<uint8_t>(1));
  for (const auto& [word, weight] : bow) EXPECT_NEAR(weight, word == w1 ? 0.75 : 0.25, 1e-12);
  EXPECT_TRUE(std::is_sorted(bow.begin(), bow.end()));
  // Direct index at the words: the three rows of cluster 1 under one node.
  ASSERT_EQ(features.size(), 2u);
  EXPECT_EQ(features.at(vocabulary.wordNode(w1)), (std::vector<int>{0, 1, 2}));
}

TEST(Vocabulary, L1Score) {
  const BowVector a{{1, 0.5}, {2, 0.5}};
  EXPECT_DOUBLE_EQ(bowScore(a, a), 1.0);
  EXPECT_DOUBLE_EQ(bowScore(a, BowVector{{1, 2.0}, {2, 2.0}}), 1.0);  // scale does not matter
  EXPECT_DOUBLE_EQ(bowScore(a, BowVector{{3, 0.5}, {4, 0.5}}), 0.0);
  EXPECT_DOUBLE_EQ(bowScore(a, BowVector{}), 0.0);
  // {1: 3/4, 2: 1/4} vs {2: 1/2, 3: 1/2}: |3/4| + |1/4 - 1/2| + |1/2| = 3/2, s = 1 - 3/4.
  EXPECT_DOUBLE_EQ(bowScore(BowVector{{1, 3.0}, {2, 1.0}}, BowVector{{2, 1.0}, {3, 1.0}}), 0.25);
}

class VocabularyFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("ply_slam_vocab_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
            "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::create_directories(dir_);
    path_ = (dir_ / "orb.voc").string();
    data_ = makeClusters();
    vocabulary_ = BinaryVocabulary::train(data_.images, params(3, 3));
    vocabulary_.save(path_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  std::vector<char> bytes() const {
    std::ifstream in(path_, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  }
  void write(const std::vector<char>& b) const {
    std::ofstream(path_, std::ios::binary | std::ios::trunc).write(b.data(), b.size());
  }
  // Loading fails with a message naming the file and containing `what`.
  void expectRejected(const std::string& path, DescriptorKind kind, const std::string& what) {
    try {
      BinaryVocabulary::load(path, kind);
      FAIL() << "accepted " << path;
    } catch (const std::runtime_error& e) {
      std::cout << "  rejected: " << e.what() << "\n";
      EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
  }

  std::filesystem::path dir_;
  std::string path_;
  ClusterData data_;
  BinaryVocabulary vocabulary_;
};

TEST_F(VocabularyFileTest, RoundTripGivesTheSameWords) {
  const BinaryVocabulary loaded = BinaryVocabulary::load(path_, DescriptorKind::kOrb);
  EXPECT_EQ(loaded.data().parents, vocabulary_.data().parents);
  EXPECT_EQ(loaded.data().centres, vocabulary_.data().centres);
  EXPECT_EQ(loaded.data().idf, vocabulary_.data().idf);
  EXPECT_EQ(loaded.branching(), 3);
  EXPECT_EQ(loaded.levels(), 3);
  for (const cv::Mat& image : data_.images) {
    BowVector a, b;
    FeatureVector fa, fb;
    vocabulary_.transform(image, a, fa, 1);
    loaded.transform(image, b, fb, 1);
    EXPECT_EQ(a, b);
    EXPECT_EQ(fa, fb);
  }
  const auto entries = std::distance(std::filesystem::directory_iterator(dir_), {});
  EXPECT_EQ(entries, 1) << "temporary file left beside " << path_;
}

TEST_F(VocabularyFileTest, MissingFileIsRejected) {
  expectRejected((dir_ / "none.voc").string(), DescriptorKind::kOrb, "missing");
}

TEST_F(VocabularyFileTest, SpecialFilesAreRejectedNamingThem) {
  const std::string fifo = (dir_ / "fifo.voc").string();
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  expectRejected(fifo, DescriptorKind::kOrb, "named pipe");
  expectRejected(dir_.string(), DescriptorKind::kOrb, "is a directory");
}

TEST_F(VocabularyFileTest, TruncatedFileIsRejected) {
  std::vector<char> b = bytes();
  b.resize(b.size() - 100);
  write(b);
  expectRejected(path_, DescriptorKind::kOrb, "truncated");
  b.resize(20);  // inside the header
  write(b);
  expectRejected(path_, DescriptorKind::kOrb, "truncated");
}

TEST_F(VocabularyFileTest, FlippedByteFailsTheChecksum) {
  std::vector<char> b = bytes();
  b[b.size() / 2] ^= 0x10;
  write(b);
  expectRejected(path_, DescriptorKind::kOrb, "checksum");
}

TEST_F(VocabularyFileTest, BadMagicIsRejected) {
  std::vector<char> b = bytes();
  b[0] = 'X';
  write(b);
  expectRejected(path_, DescriptorKind::kOrb, "magic");
}

TEST_F(VocabularyFileTest, WrongKindIsRejected) {
  expectRejected(path_, DescriptorKind::kLbd, "wrong kind");
}

}  // namespace
}  // namespace ply_slam
