// Loop scoring (PAPER.md §3.3): entropy weights of the point and line BoW vectors, the fused
// S_pl, and the candidate selection (normalisation, covisible exclusion, alpha, consistency
// over consecutive queries), with values worked out by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <unordered_map>
#include <utility>
#include <vector>

#include "ply_slam/loop/loop_candidate_selector.h"
#include "ply_slam/loop/loop_score.h"

namespace ply_slam {
namespace {

TEST(BowEntropy, KnownDistributions) {
  EXPECT_DOUBLE_EQ(bowEntropy(BowWeights{}), 0.0);
  EXPECT_DOUBLE_EQ(bowEntropy(BowWeights{{7, 0.3}}), 0.0);  // one word: no information
  // Four equal words: ln 4.
  EXPECT_NEAR(bowEntropy(BowWeights{{1, 0.1}, {2, 0.1}, {3, 0.1}, {4, 0.1}}), std::log(4.0), 1e-12);
  // 0.25 / 0.75: -(0.25 ln 0.25 + 0.75 ln 0.75) = 0.562335.
  EXPECT_NEAR(bowEntropy(BowWeights{{1, 1.0}, {2, 3.0}}), 0.5623351446188083, 1e-12);
  // Only the shape of the distribution counts, not the scale of the weights.
  EXPECT_NEAR(bowEntropy(BowWeights{{1, 10.0}, {2, 30.0}}), 0.5623351446188083, 1e-12);
  // More distinct words, evenly spread, weigh more.
  EXPECT_GT(bowEntropy(BowWeights{{1, 1}, {2, 1}, {3, 1}}), bowEntropy(BowWeights{{1, 1}, {2, 1}}));
  // All-zero weights are no distribution.
  EXPECT_DOUBLE_EQ(bowEntropy(BowWeights{{1, 0.0}, {2, 0.0}}), 0.0);
}

TEST(BowEntropy, AcceptsOtherMapLikeContainers) {
  const std::unordered_map<unsigned, float> hashed = {{1, 0.5f}, {2, 0.5f}};
  EXPECT_NEAR(bowEntropy(hashed), std::log(2.0), 1e-7);
  const std::vector<std::pair<int, double>> pairs = {{1, 1.0}, {2, 1.0}, {3, 1.0}};
  EXPECT_NEAR(bowEntropy(pairs), std::log(3.0), 1e-12);
}

TEST(PointLineScore, WeightsByEntropy) {
  EXPECT_NEAR(pointLineScore(0.2, 0.4, 1.0, 1.0), 0.3, 1e-12);            // equal entropies: mean
  EXPECT_NEAR(pointLineScore(0.2, 0.4, 3.0, 1.0), 0.25, 1e-12);           // 0.75 * 0.2 + 0.25 * 0.4
  EXPECT_NEAR(pointLineScore(0.2, 0.4, std::log(4.0), 0.0), 0.2, 1e-12);  // no line information
  EXPECT_NEAR(pointLineScore(0.2, 0.4, 0.0, 0.0), 0.3, 1e-12);            // neither: plain mean
  // Table 6: S_p 0.1087, S_l 0.1744 -> S_pl 0.1345 needs H_p : H_l = (0.1744 - 0.1345) :
  // (0.1345 - 0.1087) = 0.0399 : 0.0258, i.e. a point weight of 0.607.
  EXPECT_NEAR(pointLineScore(0.1087, 0.1744, 0.0399, 0.0258), 0.1345, 1e-12);
}

TEST(ScoreLoopCandidate, FusesBowAndInstances) {
  // Points: 4 equal words, H_p = ln 4; lines: 2 equal words, H_l = ln 2. Weights 2/3 and 1/3:
  // S_pl = (2 * 0.3 + 0.6) / 3 = 0.4. One chair 10 px off: sure match, S_inst 1.
  // S_fin = 0.6 * 0.4 + 0.4 * 1 = 0.64.
  const FeatureEntropy h =
      featureEntropy(BowWeights{{1, 1}, {2, 1}, {3, 1}, {4, 1}}, BowWeights{{9, 2}, {8, 2}});
  EXPECT_NEAR(h.points, 2.0 * h.lines, 1e-12);
  const InstanceFrame query{cv::Size(640, 480), {{"chair", cv::Rect2d(100, 100, 80, 60)}}};
  const InstanceFrame candidate{cv::Size(640, 480), {{"chair", cv::Rect2d(110, 100, 80, 60)}}};
  const LoopScore s = scoreLoopCandidate(0.3, 0.6, h, query, candidate, LoopOptions());
  EXPECT_NEAR(s.point_line, 0.4, 1e-12);
  EXPECT_DOUBLE_EQ(s.instance, 1.0);
  EXPECT_EQ(s.instance_matches, 1);
  EXPECT_NEAR(s.final_score, 0.64, 1e-12);
  // Without instances the paper's S_inst_fin is 0: S_fin = 0.6 S_pl.
  const InstanceFrame empty{cv::Size(640, 480), {}};
  EXPECT_NEAR(scoreLoopCandidate(0.3, 0.6, h, empty, empty, LoopOptions()).final_score, 0.24,
              1e-12);
}

LoopCandidate candidate(long id, double score, std::vector<long> covisible = {}) {
  return {id, score, std::move(covisible)};
}

LoopQuery query(long id, std::vector<LoopCandidate> candidates, double reference = 0.5,
                std::set<long> covisible = {}) {
  return {id, reference, std::move(covisible), std::move(candidates)};
}

TEST(ScoreCandidates, NormalisesByTheBestCovisibleScoreAndKeepsAboveAlpha) {
  LoopOptions options;
  options.min_normalised_score = 0.3;
  // Reference 0.5: 0.2 -> 0.4 passes, 0.1 -> 0.2 does not, 0.6 -> 1.2 passes.
  const auto passing = scoreCandidates(
      query(100, {candidate(1, 0.2), candidate(2, 0.1), candidate(3, 0.6, {4})}), options);
  ASSERT_EQ(passing.size(), 2u);
  EXPECT_EQ(passing[0].id, 1);
  EXPECT_NEAR(passing[0].normalised_score, 0.4, 1e-12);
  EXPECT_EQ(passing[1].id, 3);
  EXPECT_NEAR(passing[1].normalised_score, 1.2, 1e-12);
  EXPECT_EQ(passing[1].group, (std::set<long>{3, 4}));
}

TEST(ScoreCandidates, ExcludesCovisibleKeyframesAndTheQuery) {
  const auto passing = scoreCandidates(
      query(100, {candidate(100, 0.9), candidate(99, 0.9), candidate(5, 0.3)}, 0.5, {98, 99}),
      LoopOptions());
  ASSERT_EQ(passing.size(), 1u);
  EXPECT_EQ(passing[0].id, 5);
}

TEST(ScoreCandidates, NoReferenceScoreNoCandidates) {
  EXPECT_TRUE(scoreCandidates(query(100, {candidate(1, 0.9)}, 0.0), LoopOptions()).empty());
}

// Keyframes 10, 11, 12 see the same place and are covisible with each other: a revisit seen
// by consecutive queries 100, 101, 102 returns one of them each time.
LoopCandidate place(long id) {
  std::vector<long> others;
  for (long k : {10, 11, 12}) {
    if (k != id) others.push_back(k);
  }
  return candidate(id, 0.4, others);
}

TEST(LoopCandidateSelector, AcceptsOnTheThirdConsecutiveQuery) {
  LoopCandidateSelector selector{LoopOptions()};
  EXPECT_TRUE(selector.process(query(100, {place(10)})).empty());
  EXPECT_TRUE(selector.process(query(101, {place(11)})).empty());
  const auto accepted = selector.process(query(102, {place(12)}));
  ASSERT_EQ(accepted.size(), 1u);
  EXPECT_EQ(accepted[0].id, 12);
  EXPECT_NEAR(accepted[0].normalised_score, 0.8, 1e-12);
}

TEST(LoopCandidateSelector, ABrokenRunStartsAgain) {
  LoopCandidateSelector selector{LoopOptions()};
  EXPECT_TRUE(selector.process(query(100, {place(10)})).empty());
  EXPECT_TRUE(selector.process(query(101, {place(11)})).empty());
  EXPECT_TRUE(selector.process(query(102, {})).empty());  // nothing passes: the run ends
  EXPECT_TRUE(selector.process(query(103, {place(10)})).empty());
  EXPECT_TRUE(selector.process(query(104, {place(12)})).empty());
  EXPECT_EQ(selector.process(query(105, {place(11)})).size(), 1u);
}

TEST(LoopCandidateSelector, AnUnrelatedOrWeakCandidateBreaksTheRun) {
  LoopCandidateSelector selector{LoopOptions()};
  selector.process(query(100, {place(10)}));
  selector.process(query(101, {place(11)}));
  // Another place (its group shares no keyframe with 10..12): a run of its own at 1.
  EXPECT_TRUE(selector.process(query(102, {candidate(50, 0.4, {51})})).empty());
  EXPECT_TRUE(selector.process(query(103, {place(12)})).empty());
  // A candidate below alpha (0.1 / 0.5 = 0.2 < 0.3) does not continue it either.
  EXPECT_TRUE(selector.process(query(104, {candidate(10, 0.1, {11, 12})})).empty());
  EXPECT_TRUE(selector.process(query(105, {place(10)})).empty());
}

TEST(LoopCandidateSelector, CovisibleCandidatesNeverAccumulate) {
  LoopCandidateSelector selector{LoopOptions()};
  for (long q = 100; q < 106; ++q) {
    EXPECT_TRUE(selector.process(query(q, {place(10)}, 0.5, {10, 11, 12})).empty());
  }
}

TEST(LoopCandidateSelector, ResetForgetsRuns) {
  LoopCandidateSelector selector{LoopOptions()};
  selector.process(query(100, {place(10)}));
  selector.process(query(101, {place(11)}));
  selector.reset();
  EXPECT_TRUE(selector.process(query(102, {place(12)})).empty());
}

TEST(LoopCandidateSelector, KeepsAcceptingWhileTheRunLastsBestFirst) {
  LoopOptions options;
  options.consistency = 1;  // every passing candidate at once
  LoopCandidateSelector selector(options);
  const auto accepted =
      selector.process(query(100, {candidate(1, 0.2), candidate(20, 0.45), candidate(30, 0.3)}));
  ASSERT_EQ(accepted.size(), 3u);
  EXPECT_EQ(accepted[0].id, 20);
  EXPECT_EQ(accepted[1].id, 30);
  EXPECT_EQ(accepted[2].id, 1);
}

}  // namespace
}  // namespace ply_slam
