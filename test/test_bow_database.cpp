// The keyframe database of the loop module: inverted-index queries and direct-index matching.
#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <stdexcept>

#include "loop_test_data.h"
#include "ply_slam/loop/binary_vocabulary.h"
#include "ply_slam/loop/bow_database.h"
#include "ply_slam/loop/direct_index_matcher.h"

namespace ply_slam {
namespace {

constexpr int kLevelsUp = 2;

// Keyframes of random descriptors (points and lines) and vocabularies trained on them.
class BowDatabaseTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::mt19937 rng(3);
    for (int i = 0; i < 40; ++i) {
      points_.push_back(test::randomDescriptors(200, rng));
      lines_.push_back(test::randomDescriptors(40, rng));
    }
    point_vocabulary_ = BinaryVocabulary::train(points_, params(DescriptorKind::kOrb));
    line_vocabulary_ = BinaryVocabulary::train(lines_, params(DescriptorKind::kLbd));
  }

  static VocabularyParams params(DescriptorKind kind) {
    VocabularyParams p;
    p.kind = kind;
    p.branching = 6;
    p.levels = 4;
    return p;
  }

  KeyFrameWords words(const cv::Mat& points, const cv::Mat& lines) const {
    KeyFrameWords w;
    point_vocabulary_.transform(points, w.points, w.point_features, kLevelsUp);
    line_vocabulary_.transform(lines, w.lines, w.line_features, kLevelsUp);
    return w;
  }

  BowDatabase filledDatabase() const {
    BowDatabase database(point_vocabulary_.numWords(), line_vocabulary_.numWords());
    for (size_t i = 0; i < points_.size(); ++i)
      database.add(static_cast<long>(100 + i), words(points_[i], lines_[i]));
    return database;
  }

  std::vector<cv::Mat> points_, lines_;
  BinaryVocabulary point_vocabulary_, line_vocabulary_;
};

TEST_F(BowDatabaseTest, NoisyCopyFindsItsKeyFrameFirst) {
  const BowDatabase database = filledDatabase();
  std::mt19937 rng(11);
  for (int k : {0, 17, 39}) {
    const KeyFrameWords query =
        words(test::noisyCopy(points_[k], 6, rng), test::noisyCopy(lines_[k], 6, rng));
    const std::vector<BowCandidate> found = database.query(query.points, query.lines, 5);
    ASSERT_FALSE(found.empty());
    EXPECT_EQ(found[0].keyframe_id, 100 + k);
    EXPECT_GT(found[0].point_score, 0.3);
    EXPECT_GT(found[0].line_score, 0.3);
    if (found.size() > 1) {
      EXPECT_GT(found[0].point_score, 2 * found[1].point_score);
    }
    EXPECT_LE(found.size(), 5u);
  }
}

TEST_F(BowDatabaseTest, ScoresAreTheL1Scores) {
  const BowDatabase database = filledDatabase();
  std::mt19937 rng(5);
  const KeyFrameWords query =
      words(test::noisyCopy(points_[3], 20, rng), test::noisyCopy(lines_[3], 20, rng));
  for (const BowCandidate& c : database.query(query.points, query.lines, 0)) {
    const KeyFrameWords* stored = database.find(c.keyframe_id);
    ASSERT_NE(stored, nullptr);
    EXPECT_NEAR(c.point_score, bowScore(query.points, stored->points), 1e-12);
    EXPECT_NEAR(c.line_score, bowScore(query.lines, stored->lines), 1e-12);
    // To the bit: the database's sum is unitBowScore's, term by term.
    BowVector points = query.points, lines = query.lines;
    normaliseL1(points);
    normaliseL1(lines);
    EXPECT_EQ(c.point_score, unitBowScore(points, stored->points));
    EXPECT_EQ(c.line_score, unitBowScore(lines, stored->lines));
  }
}

TEST_F(BowDatabaseTest, RemovedAndExcludedKeyFramesAreNotReturned) {
  BowDatabase database = filledDatabase();
  const KeyFrameWords query = words(points_[17], lines_[17]);
  database.remove(117);
  EXPECT_EQ(database.size(), 39u);
  EXPECT_EQ(database.find(117), nullptr);
  auto has = [](const std::vector<BowCandidate>& found, long id) {
    return std::any_of(found.begin(), found.end(),
                       [&](const BowCandidate& c) { return c.keyframe_id == id; });
  };
  EXPECT_FALSE(has(database.query(query.points, query.lines, 0), 117));
  database.add(117, query);
  EXPECT_EQ(database.query(query.points, query.lines, 1)[0].keyframe_id, 117);
  const auto found =
      database.query(query.points, query.lines, 0, [](long id) { return id == 117 || id < 110; });
  EXPECT_FALSE(has(found, 117));
  EXPECT_FALSE(has(found, 105));
}

TEST_F(BowDatabaseTest, WordBeyondTheVocabularyChangesNothing) {
  BowDatabase database = filledDatabase();
  KeyFrameWords bad = words(points_[2], lines_[2]);
  bad.lines.emplace_back(static_cast<WordId>(line_vocabulary_.numWords()), 1.0);
  EXPECT_THROW(database.add(102, bad), std::out_of_range);
  ASSERT_NE(database.find(102), nullptr);  // the old entry stays
  const KeyFrameWords good = words(points_[2], lines_[2]);
  EXPECT_EQ(database.query(good.points, good.lines, 1)[0].keyframe_id, 102);
}

TEST_F(BowDatabaseTest, DirectIndexMatchingFindsTheTruePairs) {
  std::mt19937 rng(8);
  const cv::Mat& a = points_[9];
  // b: a's rows shuffled with a few bits flipped, and 100 unrelated rows among them.
  std::vector<int> order(a.rows + 100);
  std::iota(order.begin(), order.end(), 0);
  std::shuffle(order.begin(), order.end(), rng);
  const cv::Mat others = test::randomDescriptors(100, rng);
  cv::Mat b(static_cast<int>(order.size()), 32, CV_8U);
  for (size_t j = 0; j < order.size(); ++j) {
    const cv::Mat row =
        order[j] < a.rows ? test::flipBits(a.row(order[j]), 5, rng) : others.row(order[j] - a.rows);
    row.copyTo(b.row(static_cast<int>(j)));
  }
  BowVector bow_a, bow_b;
  FeatureVector features_a, features_b;
  // Random descriptors have no cluster structure: a noisy copy may descend elsewhere (at depth
  // 2 a quarter of them did, at depth 1 about 15 %), so the index is one level below the root.
  point_vocabulary_.transform(a, bow_a, features_a, 3);
  point_vocabulary_.transform(b, bow_b, features_b, 3);
  const auto matches = DirectIndexMatcher(50, 0.8).match(features_a, a, features_b, b);
  for (const auto& [i, j] : matches) EXPECT_EQ(order[j], i) << "false match";
  EXPECT_GE(matches.size(), static_cast<size_t>(0.8 * a.rows));
}

}  // namespace
}  // namespace ply_slam
