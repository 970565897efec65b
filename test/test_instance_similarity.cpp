// Instance similarity (PAPER.md §3.3) on hand-made boxes. The image is 640 x 480 so that
// diag = 800 and every expected value below is worked out by hand in the comments.
#include <gtest/gtest.h>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "ply_slam/loop/instance_similarity.h"
#include "ply_slam/loop/loop_score.h"
#include "ply_slam/semantic/instance_box.h"

namespace ply_slam {
namespace {

const cv::Size kImage(640, 480);  // diag = sqrt(640^2 + 480^2) = 800

// A 100 x 100 box of the class centred at (cx, cy).
InstanceBox box(const std::string& name, double cx, double cy) {
  return {name, cv::Rect2d(cx - 50.0, cy - 50.0, 100.0, 100.0)};
}

InstanceFrame frame(std::vector<InstanceBox> boxes) { return {kImage, std::move(boxes)}; }

// Options with the spatial-consistency adjustment switched off, to see Th_dyna alone.
LoopOptions withoutConsistency() {
  LoopOptions options;
  options.consistency_boost = 0.0;
  options.consistency_penalty = 1.0;
  return options;
}

TEST(InstanceSimilarity, NoInstancesScoresZero) {
  const InstanceSimilarity s = instanceSimilarity(frame({}), frame({}), LoopOptions());
  EXPECT_EQ(s.matches, 0);
  EXPECT_DOUBLE_EQ(s.score, 0.0);
  // Instances on one side only: nothing to match either.
  EXPECT_EQ(instanceSimilarity(frame({box("chair", 100, 100)}), frame({}), {}).matches, 0);
}

TEST(InstanceSimilarity, SurePositionMatchCreditsOne) {
  // Centres (150,150) and (160,150): D = 10, S_pos = 1 - 10/800 = 0.9875 > 0.95 -> credited 1,
  // although S_inst = 0.6 * 0.9875 + 0.4 * (9000 / 11000) = 0.9198 < 1.
  const InstanceSimilarity s = instanceSimilarity(frame({box("chair", 150, 150)}),
                                                  frame({box("chair", 160, 150)}), LoopOptions());
  EXPECT_EQ(s.matches, 1);
  EXPECT_DOUBLE_EQ(s.score, 1.0);
}

TEST(InstanceSimilarity, SureMatchUsesEachInstanceOnce) {
  // One chair against two candidates at D = 10 (S_pos 0.9875) and D = 20 (S_pos 0.975): both
  // are sure, but the one current chair matches once, the nearer. The other candidate chair is
  // left with nobody to pair with in step 2.
  const InstanceSimilarity s =
      instanceSimilarity(frame({box("chair", 150, 150)}),
                         frame({box("chair", 150, 170), box("chair", 160, 150)}), LoopOptions());
  EXPECT_EQ(s.matches, 1);
  EXPECT_DOUBLE_EQ(s.score, 1.0);
}

TEST(InstanceSimilarity, ClassesDoNotMatchEachOther) {
  const InstanceSimilarity s = instanceSimilarity(frame({box("chair", 150, 150)}),
                                                  frame({box("tv", 150, 150)}), LoopOptions());
  EXPECT_EQ(s.matches, 0);
}

TEST(InstanceSimilarity, StepTwoThresholdDependsOnInstanceCount) {
  // Centres 120 px apart, boxes disjoint: S_pos = 1 - 120/800 = 0.85, S_IoU = 0,
  // S_inst = 0.6 * 0.85 = 0.51.
  // n = 1: Th_dyna = max(0.3, min(0.6, 0.6 - 0.05)) = 0.55 > 0.51 -> no match.
  const LoopOptions options = withoutConsistency();
  EXPECT_EQ(
      instanceSimilarity(frame({box("chair", 50, 50)}), frame({box("chair", 170, 50)}), options)
          .matches,
      0);
  // n = 2 (the second chair far away): Th_dyna = 0.5 < 0.51 -> the pair matches, S = 0.51.
  // Pairs: A(50,50)-A'(170,50) 0.51; B(450,50)-A' D 280 -> 0.39; A-B'(170,290) D 268.3 ->
  // 0.399; B-B' D 368.8 -> 0.323. After A-A' only B-B' is left, 0.323 < 0.5.
  const InstanceSimilarity s =
      instanceSimilarity(frame({box("chair", 50, 50), box("chair", 450, 50)}),
                         frame({box("chair", 170, 50), box("chair", 170, 290)}), options);
  EXPECT_EQ(s.matches, 1);
  EXPECT_NEAR(s.score, 0.51, 1e-12);
}

TEST(InstanceSimilarity, StepTwoMatchesAboveThreshold) {
  // n = 1, centres 80 px apart: S_pos = 0.9 (not sure), overlap 20 x 100 = 2000 of a union
  // 18000: S_IoU = 0.1111, S_inst = 0.54 + 0.04444 = 0.58444 > Th_dyna 0.55.
  const InstanceSimilarity s = instanceSimilarity(frame({box("chair", 50, 50)}),
                                                  frame({box("chair", 130, 50)}), LoopOptions());
  EXPECT_EQ(s.matches, 1);
  EXPECT_NEAR(s.score, 0.54 + 0.4 * 2000.0 / (18000.0 + 1e-6), 1e-12);
}

TEST(InstanceSimilarity, ConsistentNeighbourhoodBoosts) {
  // Both frames: two chairs 400 px apart (0.5 diag): S_aver = 1 > Th_aver 0.9 -> +0.1.
  // A(50,50)-A'(170,50) and B(450,50)-B'(570,50): S_inst 0.51 -> 0.61 > Th_dyna(2,2) 0.5.
  // Cross pairs: A-B' 0.6 * 0.35 + 0.1 = 0.31, B-A' 0.6 * 0.65 + 0.1 = 0.49, never best.
  const InstanceSimilarity s =
      instanceSimilarity(frame({box("chair", 50, 50), box("chair", 450, 50)}),
                         frame({box("chair", 170, 50), box("chair", 570, 50)}), LoopOptions());
  EXPECT_EQ(s.matches, 2);
  EXPECT_NEAR(s.score, 0.61, 1e-12);
}

TEST(InstanceSimilarity, InconsistentNeighbourhoodPenalises) {
  // The layout of StepTwoThresholdDependsOnInstanceCount: neighbour distance 0.5 diag in the
  // current frame, 240 px = 0.3 diag in the candidate: S_aver = 0.8 < 0.9 -> S_inst * 0.8.
  // A-A' 0.51 -> 0.408 < 0.5: what matched without the adjustment no longer does.
  const InstanceSimilarity s =
      instanceSimilarity(frame({box("chair", 50, 50), box("chair", 450, 50)}),
                         frame({box("chair", 170, 50), box("chair", 170, 290)}), LoopOptions());
  EXPECT_EQ(s.matches, 0);
  EXPECT_DOUBLE_EQ(s.score, 0.0);
}

TEST(InstanceSimilarity, SureAndGreedyMatchesAverage) {
  // A(150,150)-A'(160,150): sure (S_pos 0.9875), credited 1.
  // B(550,150)-B'(490,150): D 60, S_pos 0.925 (not sure), overlap 40 x 100 = 4000 of 16000:
  // S_IoU 0.25, S_inst = 0.6 * 0.925 + 0.4 * 0.25 = 0.655; neighbourhoods 400/800 = 0.5 vs 330/800
  // = 0.4125: S_aver 0.9125 > 0.9 -> +0.1 = 0.755 > Th_dyna 0.5. S_inst_fin = (1 + 0.755) / 2 =
  // 0.8775.
  const InstanceSimilarity s =
      instanceSimilarity(frame({box("chair", 150, 150), box("chair", 550, 150)}),
                         frame({box("chair", 160, 150), box("chair", 490, 150)}), LoopOptions());
  EXPECT_EQ(s.matches, 2);
  EXPECT_NEAR(s.score, (1.0 + 0.6 * 0.925 + 0.4 * 4000.0 / (16000.0 + 1e-6) + 0.1) / 2.0, 1e-12);
}

TEST(InstanceSimilarity, DynamicClassesAreDropped) {
  // People and dogs at identical boxes would be sure matches; they are left out, the chair
  // (sure, 1) alone counts.
  const std::vector<InstanceBox> boxes = {box("person", 300, 200), box("dog", 400, 300),
                                          box("chair", 150, 150)};
  const InstanceSimilarity s = instanceSimilarity(frame(boxes), frame(boxes), LoopOptions());
  EXPECT_EQ(s.matches, 1);
  EXPECT_DOUBLE_EQ(s.score, 1.0);
  const InstanceSimilarity people =
      instanceSimilarity(frame({box("person", 300, 200)}), frame({box("person", 300, 200)}), {});
  EXPECT_EQ(people.matches, 0);
}

TEST(InstanceSimilarity, DifferentImageSizesAreRejected) {
  EXPECT_THROW(instanceSimilarity(frame({}), InstanceFrame{cv::Size(320, 240), {}}, {}),
               std::invalid_argument);
}

TEST(DynamicThreshold, FollowsThePaperFormula) {
  const LoopOptions o;
  EXPECT_NEAR(dynamicThreshold(0, 3, o), 0.6, 1e-12);
  EXPECT_NEAR(dynamicThreshold(1, 1, o), 0.55, 1e-12);
  EXPECT_NEAR(dynamicThreshold(2, 5, o), 0.5, 1e-12);  // min(n1, n2) = 2
  EXPECT_NEAR(dynamicThreshold(4, 4, o), 0.4, 1e-12);
  EXPECT_NEAR(dynamicThreshold(6, 9, o), 0.3, 1e-12);
  EXPECT_NEAR(dynamicThreshold(20, 30, o), 0.3, 1e-12);  // the floor
}

TEST(NeighbourhoodSimilarity, SortedVectorsOverTheShorterLength) {
  // {0.5, 0.2} -> {0.2, 0.5}; {0.9, 0.1, 0.25} -> {0.1, 0.25, 0.9}; first two compared:
  // 1 - (0.1 + 0.25) / 2 = 0.825.
  EXPECT_NEAR(*neighbourhoodSimilarity({0.5, 0.2}, {0.9, 0.1, 0.25}), 0.825, 1e-12);
  EXPECT_FALSE(neighbourhoodSimilarity({}, {0.3}).has_value());
  EXPECT_FALSE(neighbourhoodSimilarity({0.3}, {}).has_value());
}

TEST(FinalLoopScore, PaperTable6Example) {
  // S_fin = 0.6 * 0.1345 + 0.4 * 0.92 = 0.0807 + 0.368 = 0.4487.
  EXPECT_NEAR(finalLoopScore(0.1345, 0.92, LoopOptions()), 0.4487, 1e-12);
}

}  // namespace
}  // namespace ply_slam
