// LoopDetector on a made-up world: a strip of landmarks with binary descriptors, keyframes that
// see overlapping windows of it, and a second pass over windows seen before (the loop).
#include <gtest/gtest.h>

#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

#include "default_vocabularies.h"
#include "loop_test_data.h"
#include "ply_slam/features/orb_extractor.h"
#include "ply_slam/loop/loop_detector.h"
#include "ply_slam/loop/loop_key_frame_builder.h"
#include "ply_slam/system/system_config.h"

namespace ply_slam {
namespace {

constexpr int kWindow = 200;  // landmarks a keyframe sees
constexpr int kStride = 100;  // consecutive keyframes share half of them
constexpr int kLandmarks = 2000;

class LoopDetectorTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::mt19937 rng(7);
    points_ = test::randomDescriptors(kLandmarks, rng);
    lines_ = test::randomDescriptors(kLandmarks / 5, rng);
    std::uniform_real_distribution<double> y(-0.8, 0.8), z(2.0, 4.0), dx(-0.004, 0.004);
    for (int j = 0; j < kLandmarks; ++j) world_.emplace_back(0.01 * j + dx(rng), y(rng), z(rng));
    std::vector<cv::Mat> point_images, line_images;
    for (int s = 0; s + kWindow <= kLandmarks; s += kStride) {
      point_images.push_back(points_.rowRange(s, s + kWindow));
      line_images.push_back(lines_.rowRange(s / 5, s / 5 + kWindow / 5));
    }
    orb_ = BinaryVocabulary::train(point_images, params(DescriptorKind::kOrb));
    lbd_ = BinaryVocabulary::train(line_images, params(DescriptorKind::kLbd));
  }

  static VocabularyParams params(DescriptorKind kind) {
    VocabularyParams p;
    p.kind = kind;
    p.branching = 8;
    p.levels = 3;
    return p;
  }

  // A keyframe seeing landmarks [start, start + kWindow) from a camera at x = the window's
  // centre (+ offset), looking along +z; descriptors re-observed with a few bits flipped.
  LoopKeyFrame view(long id, int start, const Eigen::Vector3d& offset, std::mt19937& rng) const {
    LoopKeyFrame kf;
    kf.id = id;
    kf.stamp = 2.0 * id;  // s: the second pass comes 28 s after the first
    const Eigen::Vector3d centre(0.01 * (start + kWindow / 2), 0.0, 0.0);
    kf.orb_descriptors = test::noisyCopy(points_.rowRange(start, start + kWindow), 4, rng);
    kf.lbd_descriptors = test::noisyCopy(lines_.rowRange(start / 5, (start + kWindow) / 5), 4, rng);
    for (int j = start; j < start + kWindow; ++j) {
      const Eigen::Vector3d p_c = world_[j] - centre - offset;
      kf.keypoints.push_back(camera_.project(p_c));
      kf.depth.push_back(static_cast<float>(p_c.z()));
    }
    return kf;
  }

  // Keyframes 0..14 along the strip (windows 0, 100, ..., 1400), each covisible with its
  // neighbours in time; then 15..18 back over windows 100..400 from 5 cm aside, covisible only
  // with each other (tracking did not connect them to the first pass).
  LoopDetector filledDetector(LoopOptions options = {}) const {
    options.depth_noise = camera_.depth_noise;
    LoopDetector detector(orb_, lbd_, camera_, options);
    std::mt19937 rng(11);
    for (long i = 0; i <= 18; ++i) {
      const bool second_pass = i >= 15;
      LoopKeyFrame kf = view(i, static_cast<int>(second_pass ? (i - 14) * kStride : i * kStride),
                             second_pass ? kOffset : Eigen::Vector3d::Zero(), rng);
      if (i != 0 && i != 15) kf.covisibility[i - 1] = kWindow - kStride;
      if (i != 14 && i != 18) kf.covisibility[i + 1] = kWindow - kStride;
      detector.addKeyFrame(std::move(kf));
    }
    return detector;
  }

  const Eigen::Vector3d kOffset{0.05, 0.0, 0.0};
  PinholeCamera camera_ = test::loopTestCamera();
  cv::Mat points_, lines_;
  std::vector<Eigen::Vector3d> world_;
  BinaryVocabulary orb_, lbd_;
};

TEST_F(LoopDetectorTest, ScoresTheRevisitedWindowHighest) {
  const LoopDetector detector = filledDetector();
  const LoopQueryScores s = detector.score(17);  // window 300, first seen by keyframe 3
  ASSERT_TRUE(s.reference_id.has_value());
  EXPECT_EQ(*s.reference_id, 16);
  ASSERT_FALSE(s.candidates.empty());
  const ScoredCandidate* best = &s.candidates[0];
  for (const ScoredCandidate& c : s.candidates) {
    if (c.raw.full > best->raw.full) best = &c;
    EXPECT_NE(c.id, 16);  // covisible
    EXPECT_NE(c.id, 18);  // later
    EXPECT_NE(c.id, 17);
  }
  EXPECT_EQ(best->id, 3);
  // The same landmarks as the query: a better match than the half-overlapping neighbour.
  EXPECT_GT(best->raw.points, s.reference.points);
  EXPECT_GT(best->raw.full / s.reference.full, 1.0);
}

// The reference is the earlier covisible keyframe most like the query, not the one sharing the
// most landmarks: here keyframe 14 (another window) is said to share the most.
TEST_F(LoopDetectorTest, TheReferenceIsTheMostSimilarEarlierCovisibleKeyFrame) {
  LoopDetector detector = filledDetector();
  const VariantScores neighbour = detector.score(17).reference;
  detector.setCovisibility(17, {{14, 10 * kWindow}, {16, kWindow - kStride}, {18, 1}});
  const LoopQueryScores s = detector.score(17);
  ASSERT_TRUE(s.reference_id.has_value());
  EXPECT_EQ(*s.reference_id, 16);
  EXPECT_EQ(s.reference.full, neighbour.full);
  EXPECT_EQ(s.reference.points, neighbour.points);
}

TEST_F(LoopDetectorTest, QueriesSeeOnlyKeyFramesOldEnough) {
  const LoopDetector detector = filledDetector();
  // Keyframe 2 (window 200) shares landmarks with 16 (window 200) and 17 (300): both later.
  for (const ScoredCandidate& c : detector.score(2).candidates) EXPECT_LT(c.id, 2);
  // Keyframe 12 (24 s): 6 (12 s) and older are candidates; 7 (14 s) is exactly 10 s older, not
  // more (ply_slam_loops' true loops are more than 10 s apart), 8 (16 s) to 10 are too recent.
  for (const ScoredCandidate& c : detector.score(12).candidates) EXPECT_LE(c.id, 6);
  LoopOptions younger;
  younger.min_candidate_age_s = 9.9;
  bool seven = false;
  for (const ScoredCandidate& c : filledDetector(younger).score(12).candidates) seven |= c.id == 7;
  EXPECT_TRUE(seven);
  LoopOptions no_age;
  no_age.min_candidate_age_s = 0.0;
  bool recent = false;
  for (const ScoredCandidate& c : filledDetector(no_age).score(12).candidates) recent |= c.id == 10;
  EXPECT_TRUE(recent);  // keyframe 10 is not covisible with 12 (windows 1000 and 1200)
  // Keyframe 15 has no earlier covisible keyframe: no reference, nothing can pass.
  EXPECT_FALSE(detector.score(15).reference_id.has_value());
}

TEST_F(LoopDetectorTest, ARemovedKeyFrameIsNoLongerFound) {
  LoopDetector detector = filledDetector();
  detector.removeKeyFrame(3);   // culled: the first pass over window 300
  detector.removeKeyFrame(99);  // never added: ignored
  EXPECT_EQ(detector.size(), 18u);
  EXPECT_THROW(detector.keyFrame(3), std::out_of_range);
  for (const ScoredCandidate& c : detector.score(17).candidates) EXPECT_NE(c.id, 3);
  for (long id : detector.recognise(detector.keyFrame(17).orb_descriptors, 20)) EXPECT_NE(id, 3);
  // Keyframe 4's only earlier covisible keyframe was 3: it is scored without a reference.
  EXPECT_FALSE(detector.score(4).reference_id.has_value());
  EXPECT_EQ(*detector.score(5).reference_id, 4);
}

TEST_F(LoopDetectorTest, AcceptsTheLoopOnTheThirdConsistentQueryWithItsMotion) {
  LoopDetector detector = filledDetector();
  for (long q = 1; q <= 14; ++q) EXPECT_FALSE(detector.detect(q).loop) << "query " << q;
  EXPECT_FALSE(detector.detect(15).loop);  // no reference
  EXPECT_FALSE(detector.detect(16).loop);  // run 1
  EXPECT_FALSE(detector.detect(17).loop);  // run 2
  const LoopDetection d = detector.detect(18);
  ASSERT_TRUE(d.loop.has_value());
  EXPECT_EQ(*d.loop, 4);  // window 400
  ASSERT_TRUE(d.geometry.has_value());
  // p_query = T p_candidate: the query camera stood kOffset further along x.
  EXPECT_LT((d.geometry->T_query_candidate.translation() + kOffset).norm(), 0.01);
  EXPECT_LT(Eigen::AngleAxisd(d.geometry->T_query_candidate.linear()).angle(), 0.01);
  EXPECT_GE(d.geometry->inliers_3d, 100);
}

TEST_F(LoopDetectorTest, OnlyLinksOfEnoughSharedLandmarksMakeKeyFramesCovisible) {
  LoopDetector detector = filledDetector();
  const auto offers = [&](long query, long candidate) {
    for (const ScoredCandidate& c : detector.score(query).candidates)
      if (c.id == candidate) return true;
    return false;
  };
  ASSERT_TRUE(offers(17, 3));
  const int weak = detector.options().min_covisible_shared - 1;
  detector.setCovisibility(17, {{16, 100}, {3, weak}});
  EXPECT_TRUE(offers(17, 3));
  EXPECT_EQ(detector.keyFrame(17).covisibility.count(3), 0u);
  detector.setCovisibility(17, {{16, 100}, {3, weak + 1}});
  EXPECT_FALSE(offers(17, 3));
}

TEST_F(LoopDetectorTest, GeometricCheckRejectsAPlaceThatOnlyLooksAlike) {
  const LoopDetector detector = filledDetector();
  // Keyframe 17 sees the landmarks of 3; 12 sees others: no consensus on a motion.
  EXPECT_TRUE(detector.verify(17, 3).accepted);
  EXPECT_FALSE(detector.verify(17, 12).accepted);
}

TEST_F(LoopDetectorTest, AlphaAboveAnyNormalisedScoreAcceptsNothing) {
  LoopOptions strict;
  strict.min_normalised_score = 100.0;
  LoopDetector detector = filledDetector(strict);
  for (long q = 1; q <= 18; ++q) EXPECT_FALSE(detector.detect(q).loop) << "query " << q;
}

TEST_F(LoopDetectorTest, RejectsKeyFramesWithoutOneDepthPerDescriptor) {
  LoopDetector detector(orb_, lbd_, camera_, LoopOptions{});
  std::mt19937 rng(1);
  LoopKeyFrame kf = view(0, 0, Eigen::Vector3d::Zero(), rng);
  kf.depth.pop_back();
  EXPECT_THROW(detector.addKeyFrame(kf), std::invalid_argument);
  EXPECT_EQ(detector.size(), 0u);
  EXPECT_THROW(detector.score(0), std::out_of_range);
}

// The default vocabularies scripts/setup.sh trains: they load as their kind, and an image's
// ORB words are closer to those of a shifted copy of it than to another image's.
TEST(DefaultVocabularies, LoadAndTellImagesApart) {
  const std::string orb_path = defaultVocabularyPath(DescriptorKind::kOrb);
  const std::string lbd_path = defaultVocabularyPath(DescriptorKind::kLbd);
  PLY_SLAM_REQUIRE_VOCABULARY(orb_path);
  PLY_SLAM_REQUIRE_VOCABULARY(lbd_path);
  const BinaryVocabulary orb = BinaryVocabulary::load(orb_path, DescriptorKind::kOrb);
  const BinaryVocabulary lbd = BinaryVocabulary::load(lbd_path, DescriptorKind::kLbd);
  EXPECT_GT(orb.numWords(), 1000u);
  EXPECT_GT(lbd.numWords(), 100u);
  EXPECT_THROW(BinaryVocabulary::load(orb_path, DescriptorKind::kLbd), std::runtime_error);

  const std::string data = "/usr/share/doc/opencv-doc/examples/data/";
  const cv::Mat a = cv::imread(data + "graf1.png", cv::IMREAD_GRAYSCALE);
  const cv::Mat b = cv::imread(data + "box_in_scene.png", cv::IMREAD_GRAYSCALE);
  ASSERT_FALSE(a.empty() || b.empty()) << "opencv-doc example images missing in " << data;
  const cv::Mat shifted = a(cv::Rect(20, 15, a.cols - 40, a.rows - 30)).clone();
  const OrbExtractor extractor{OrbOptions{}};
  const auto words = [&](const cv::Mat& gray) {
    std::vector<cv::KeyPoint> keypoints;
    cv::Mat descriptors;
    extractor.extract(gray, keypoints, descriptors);
    return orb.transform(descriptors);
  };
  const BowVector wa = words(a);
  EXPECT_GT(bowScore(wa, words(shifted)), 2.0 * bowScore(wa, words(b)));
}

TEST(LoopKeyFrameBuilder, LeavesOutMoversAndBoxesEveryInstance) {
  KeyFramePacket packet;
  packet.id = 7;
  packet.stamp = 1.5;
  packet.label_image = cv::Mat::zeros(40, 60, CV_16UC1);
  packet.label_image(cv::Rect(10, 10, 5, 5)).setTo(1);
  packet.label_image(cv::Rect(40, 20, 5, 5)).setTo(2);
  packet.instances = {{1, "person", 1.0f, true}, {2, "chair", 1.0f, false}};
  // On the person, within the 2 px dilation, beyond it, on the chair (which does not move).
  packet.keypoints = {{12, 12}, {8.2, 12}, {6.0, 12}, {42, 22}};
  packet.keypoint_depth = {1.0f, 2.0f, 3.0f, 4.0f};
  packet.descriptors = cv::Mat::zeros(4, 32, CV_8U);
  for (int r = 0; r < 4; ++r) packet.descriptors.at<uint8_t>(r, 0) = static_cast<uint8_t>(r);
  const LoopKeyFrameBuilder builder(LineOptions(), PinholeCamera(), LoopOptions(), 2);
  const LoopKeyFrame kf = builder.build(packet);
  EXPECT_EQ(kf.id, 7);
  ASSERT_EQ(kf.keypoints.size(), 2u);
  EXPECT_EQ(kf.keypoints[0], Eigen::Vector2d(6.0, 12));
  EXPECT_EQ(kf.depth, (std::vector<float>{3.0f, 4.0f}));
  ASSERT_EQ(kf.orb_descriptors.rows, 2);
  EXPECT_EQ(kf.orb_descriptors.at<uint8_t>(1, 0), 3);
  EXPECT_TRUE(kf.lbd_descriptors.empty());  // the packet has no image
  ASSERT_EQ(kf.instances.size(), 2u);
  EXPECT_EQ(kf.instances[0].class_name, "person");
  EXPECT_EQ(kf.instances[1].box, cv::Rect2d(40, 20, 5, 5));

  packet.label_image.release();  // not segmented: every feature stays, no boxes
  const LoopKeyFrame plain = builder.build(packet);
  EXPECT_EQ(plain.keypoints.size(), 4u);
  EXPECT_TRUE(plain.instances.empty());
}

// Lines describe the place even when tracking runs without them (LineOptions::enabled false, the
// shipped default), except those on a person.
TEST(LoopKeyFrameBuilder, DescribesLinesWhateverTrackingDoesAndNotOnMovers) {
  KeyFramePacket packet;
  packet.rgb = cv::Mat(480, 640, CV_8UC3, cv::Scalar(40, 40, 40));
  for (int k = 0; k < 4; ++k)  // four bright bars: eight long edges
    cv::rectangle(packet.rgb, cv::Rect(60 + 140 * k, 60, 40, 360), cv::Scalar(220, 220, 220),
                  cv::FILLED);
  LineOptions lines;
  lines.enabled = false;
  const LoopKeyFrameBuilder builder(lines, test::loopTestCamera(), LoopOptions(), 0);
  const int all = builder.build(packet).lbd_descriptors.rows;
  EXPECT_GE(all, 8);

  packet.label_image = cv::Mat::zeros(480, 640, CV_16UC1);
  packet.label_image(cv::Rect(40, 0, 90, 480)).setTo(1);  // over the first bar's two edges
  packet.instances = {{1, "person", 1.0f, true}};
  const int off_person = builder.build(packet).lbd_descriptors.rows;
  EXPECT_LT(off_person, all);
  EXPECT_GE(off_person, 6);
}

TEST(VocabularyPath, EmptyMeansTheDefaultAndRelativeMeansThePackage) {
  const std::string orb = vocabularyPath("", DescriptorKind::kOrb);
  EXPECT_EQ(orb, defaultVocabularyPath(DescriptorKind::kOrb));
  EXPECT_NE(orb.find("build/vocabulary/orb_k10_l5.voc"), std::string::npos);
  EXPECT_NE(vocabularyPath("", DescriptorKind::kLbd).find("lbd_k10_l5.voc"), std::string::npos);
  EXPECT_EQ(vocabularyPath("/abs/x.voc", DescriptorKind::kOrb), "/abs/x.voc");
  const std::string relative = vocabularyPath("voc/x.voc", DescriptorKind::kOrb);
  EXPECT_TRUE(std::filesystem::path(relative).is_absolute());
  EXPECT_TRUE(std::filesystem::exists(std::filesystem::path(relative).parent_path().parent_path() /
                                      "package.xml"));
}

}  // namespace
}  // namespace ply_slam
