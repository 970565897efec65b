#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "ply_slam/io/tum_sequence.h"
#include "ply_slam/io/tum_trajectory_file.h"
#include "shared_data.h"

namespace ply_slam {
namespace {

namespace fs = std::filesystem;

// A throw-away TUM-layout folder under /tmp, removed after each test.
class TumFolderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("ply_slam_test_tum_" + std::to_string(::getpid()) + "_" + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "rgb");
    fs::create_directories(dir_ / "depth");
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string path(const std::string& relative) const { return (dir_ / relative).string(); }

  void writeText(const std::string& relative, const std::string& text) const {
    std::ofstream(path(relative)) << text;
  }

  // rgb/<name>.png, 8UC3 (or another type for error tests).
  void writeRgb(const std::string& name, int type = CV_8UC3, cv::Size size = {8, 6}) const {
    cv::Mat image(size, type, cv::Scalar::all(100));
    ASSERT_TRUE(cv::imwrite(path("rgb/" + name + ".png"), image));
  }
  // depth/<name>.png, 16UC1 with raw value `raw` (and a zero pixel at (0,0)).
  void writeDepth(const std::string& name, int type = CV_16UC1, cv::Size size = {8, 6},
                  int raw = 5000) const {
    cv::Mat image(size, type, cv::Scalar::all(raw));
    if (type == CV_16UC1) image.at<uint16_t>(0, 0) = 0;
    ASSERT_TRUE(cv::imwrite(path("depth/" + name + ".png"), image));
  }

  // A consistent folder: rgb at 1.00 1.03 1.06 1.09, depth at 1.01 1.07. Nearest pairing:
  // 1.00 and 1.03 -> 1.01 (0.01 s, 0.02 s); 1.06 and 1.09 -> 1.07 (0.01 s, 0.02 s).
  void writeStandardFolder() const {
    writeText("rgb.txt",
              "# color images\n# timestamp filename\n"
              "1.00 rgb/a.png\n1.03 rgb/b.png\n1.06 rgb/c.png\n1.09 rgb/d.png\n");
    writeText("depth.txt", "# depth maps\n1.01 depth/x.png\n1.07 depth/y.png\n");
    for (const char* n : {"a", "b", "c", "d"}) writeRgb(n);
    for (const char* n : {"x", "y"}) writeDepth(n);
  }

  fs::path dir_;
};

// Expects `fn` to throw std::runtime_error whose message contains `fragment`.
template <typename Fn>
void expectThrowContaining(Fn fn, const std::string& fragment) {
  try {
    fn();
    ADD_FAILURE() << "no exception, expected one mentioning '" << fragment << "'";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos)
        << "message '" << e.what() << "' lacks '" << fragment << "'";
  }
}

TEST_F(TumFolderTest, NearestAssociationKeepsEveryRgbFrameAndSharesDepth) {
  writeStandardFolder();
  TumSequence seq(dir_.string(), 0.025);
  EXPECT_FALSE(seq.usedAssociationsFile());
  EXPECT_FALSE(seq.hasGroundTruth());
  ASSERT_EQ(seq.size(), 4u);
  EXPECT_EQ(seq.unassociatedRgbFrames(), 0u);
  EXPECT_EQ(seq.record(0).depth_path, path("depth/x.png"));
  EXPECT_EQ(seq.record(1).depth_path, path("depth/x.png"));  // shares x with frame 0
  EXPECT_EQ(seq.record(2).depth_path, path("depth/y.png"));
  EXPECT_EQ(seq.record(3).depth_path, path("depth/y.png"));  // shares y with frame 2
  EXPECT_EQ(seq.record(1).rgb_path, path("rgb/b.png"));
  EXPECT_DOUBLE_EQ(seq.record(3).rgb_stamp, 1.09);
  EXPECT_DOUBLE_EQ(seq.record(3).depth_stamp, 1.07);

  const RgbdImages images = seq.load(1, 5000.0);
  EXPECT_DOUBLE_EQ(images.stamp, 1.03);
  EXPECT_EQ(images.rgb.type(), CV_8UC3);
  ASSERT_EQ(images.depth.type(), CV_32FC1);
  EXPECT_EQ(images.depth.size(), images.rgb.size());
  EXPECT_FLOAT_EQ(images.depth.at<float>(0, 0), 0.0f);  // invalid stays 0
  EXPECT_FLOAT_EQ(images.depth.at<float>(3, 4), 1.0f);  // 5000 / 5000
}

TEST_F(TumFolderTest, UnsortedRgbListIsSorted) {
  writeStandardFolder();
  writeText("rgb.txt", "1.06 rgb/c.png\n1.00 rgb/a.png\n1.09 rgb/d.png\n1.03 rgb/b.png\n");
  TumSequence seq(dir_.string(), 0.025);
  ASSERT_EQ(seq.size(), 4u);
  for (size_t i = 1; i < seq.size(); ++i) {
    EXPECT_LT(seq.record(i - 1).rgb_stamp, seq.record(i).rgb_stamp);
  }
}

TEST_F(TumFolderTest, DuplicateRgbStampThrows) {
  writeStandardFolder();
  writeText("rgb.txt", "1.00 rgb/a.png\n1.00 rgb/b.png\n");
  expectThrowContaining([&] { TumSequence seq(dir_.string()); }, "rgb.txt: duplicate stamp");
}

TEST_F(TumFolderTest, MaxStampDifferenceRespectedAndUnassociatedCounted) {
  writeStandardFolder();
  // With 0.015 s: 1.00 -> x (0.01), 1.03 none (0.02), 1.06 -> y (0.01), 1.09 none (0.02).
  TumSequence seq(dir_.string(), 0.015);
  ASSERT_EQ(seq.size(), 2u);
  EXPECT_EQ(seq.unassociatedRgbFrames(), 2u);
  EXPECT_DOUBLE_EQ(seq.record(0).rgb_stamp, 1.00);
  EXPECT_DOUBLE_EQ(seq.record(1).rgb_stamp, 1.06);
}

TEST_F(TumFolderTest, NoAssociableFrameThrows) {
  writeStandardFolder();
  expectThrowContaining([&] { TumSequence seq(dir_.string(), 0.001); }, dir_.string());
}

TEST_F(TumFolderTest, AssociationsFilePreferred) {
  writeStandardFolder();
  // Deliberately not the nearest pairing, and only two of the four rgb frames.
  writeText("associations.txt",
            "# rgb depth\n1.06 rgb/c.png 1.01 depth/x.png\n1.00 rgb/a.png 1.07 depth/y.png\n");
  TumSequence seq(dir_.string(), 0.025);
  EXPECT_TRUE(seq.usedAssociationsFile());
  ASSERT_EQ(seq.size(), 2u);
  EXPECT_EQ(seq.unassociatedRgbFrames(), 2u);
  EXPECT_EQ(seq.record(0).rgb_path, path("rgb/a.png"));  // sorted by rgb stamp
  EXPECT_EQ(seq.record(0).depth_path, path("depth/y.png"));
  EXPECT_EQ(seq.record(1).rgb_path, path("rgb/c.png"));
  EXPECT_EQ(seq.record(1).depth_path, path("depth/x.png"));
  EXPECT_NO_THROW(seq.load(1, 5000.0));
}

TEST_F(TumFolderTest, GroundTruthRead) {
  writeStandardFolder();
  writeText("groundtruth.txt",
            "# timestamp tx ty tz qx qy qz qw\n1.00 1 2 3 0 0 0 1\n1.05 1.5 2 3 0 0 0 1\n");
  TumSequence seq(dir_.string());
  ASSERT_TRUE(seq.hasGroundTruth());
  ASSERT_EQ(seq.groundTruth().size(), 2u);
  EXPECT_DOUBLE_EQ(seq.groundTruth()[1].T_wc.translation().x(), 1.5);
}

// An empty or directory groundtruth.txt gave no ATE and no word why (issue #53).
TEST_F(TumFolderTest, AGroundTruthThatGivesNoneSaysWhy) {
  writeStandardFolder();
  writeText("groundtruth.txt", "# timestamp tx ty tz qx qy qz qw\n");
  EXPECT_EQ(TumSequence(dir_.string()).groundTruthProblem(),
            path("groundtruth.txt") + ": holds no poses");
  fs::remove(path("groundtruth.txt"));
  fs::create_directories(path("groundtruth.txt"));
  const TumSequence seq(dir_.string());
  EXPECT_FALSE(seq.hasGroundTruth());
  EXPECT_EQ(seq.groundTruthProblem(),
            path("groundtruth.txt") + ": is a directory, not a regular file");
  fs::remove(path("groundtruth.txt"));
  EXPECT_EQ(TumSequence(dir_.string()).groundTruthProblem(), "");
}

TEST_F(TumFolderTest, MissingFolderThrows) {
  const std::string missing = path("does_not_exist");
  expectThrowContaining([&] { TumSequence seq(missing); }, missing);
}

TEST_F(TumFolderTest, MissingRgbListThrows) {
  writeText("depth.txt", "1.01 depth/x.png\n");
  expectThrowContaining([&] { TumSequence seq(dir_.string()); }, path("rgb.txt"));
}

TEST_F(TumFolderTest, MissingDepthListThrows) {
  writeText("rgb.txt", "1.00 rgb/a.png\n");
  expectThrowContaining([&] { TumSequence seq(dir_.string()); }, path("depth.txt"));
}

TEST_F(TumFolderTest, MalformedLineNamesFileAndLine) {
  writeStandardFolder();
  writeText("depth.txt", "# depth maps\n1.01 depth/x.png\nnot-a-stamp depth/y.png\n");
  expectThrowContaining([&] { TumSequence seq(dir_.string()); }, path("depth.txt") + ":3");
  writeText("depth.txt", "1.01 depth/x.png\n1.07\n");
  expectThrowContaining([&] { TumSequence seq(dir_.string()); }, path("depth.txt") + ":2");
  writeText("associations.txt", "1.00 rgb/a.png 1.01\n");
  expectThrowContaining([&] { TumSequence seq(dir_.string()); }, path("associations.txt") + ":1");
}

TEST_F(TumFolderTest, EmptyRgbListThrows) {
  writeStandardFolder();
  writeText("rgb.txt", "# nothing\n");
  expectThrowContaining([&] { TumSequence seq(dir_.string()); }, "no frames");
}

TEST_F(TumFolderTest, MissingImageThrowsNamingIt) {
  writeStandardFolder();
  fs::remove(path("depth/y.png"));
  TumSequence seq(dir_.string(), 0.025);
  EXPECT_NO_THROW(seq.load(0, 5000.0));
  expectThrowContaining([&] { seq.load(2, 5000.0); }, path("depth/y.png") + ": image missing");
  fs::remove(path("rgb/a.png"));
  expectThrowContaining([&] { seq.load(0, 5000.0); }, path("rgb/a.png") + ": image missing");
}

// A named pipe in a list's or an image's place blocked the run for ever (issue #53); a
// directory as an image was "image missing".
TEST_F(TumFolderTest, SpecialFilesAreRefusedNamingThem) {
  writeStandardFolder();
  fs::remove(path("rgb/a.png"));
  ASSERT_EQ(::mkfifo(path("rgb/a.png").c_str(), 0600), 0);
  fs::remove(path("depth/x.png"));
  fs::create_directories(path("depth/x.png"));
  TumSequence seq(dir_.string(), 0.025);
  expectThrowContaining([&] { seq.load(0, 5000.0); }, path("rgb/a.png") + ": is a named pipe");
  fs::remove(path("rgb/a.png"));
  writeRgb("a");
  expectThrowContaining([&] { seq.load(0, 5000.0); }, path("depth/x.png") + ": is a directory");
  fs::remove(path("depth.txt"));
  ASSERT_EQ(::mkfifo(path("depth.txt").c_str(), 0600), 0);
  expectThrowContaining([&] { TumSequence again(dir_.string()); },
                        path("depth.txt") + ": is a named pipe");
  expectThrowContaining([&] { readTumTrajectory(path("depth.txt")); }, "named pipe");
}

TEST_F(TumFolderTest, UnreadableImageThrowsNamingIt) {
  writeStandardFolder();
  writeText("rgb/a.png", "this is not a png");
  TumSequence seq(dir_.string(), 0.025);
  expectThrowContaining([&] { seq.load(0, 5000.0); }, path("rgb/a.png") + ": image unreadable");
}

TEST_F(TumFolderTest, EightBitDepthThrowsWithActualType) {
  writeStandardFolder();
  writeDepth("x", CV_8UC1);
  TumSequence seq(dir_.string(), 0.025);
  expectThrowContaining([&] { seq.load(0, 5000.0); }, path("depth/x.png"));
  expectThrowContaining([&] { seq.load(0, 5000.0); }, "8UC1");
  writeDepth("x", CV_8UC3);
  expectThrowContaining([&] { seq.load(0, 5000.0); }, "wrong type 8UC3");
}

TEST_F(TumFolderTest, GrayscaleRgbThrowsAndBgraIsConverted) {
  writeStandardFolder();
  writeRgb("a", CV_8UC1);
  TumSequence seq(dir_.string(), 0.025);
  expectThrowContaining([&] { seq.load(0, 5000.0); }, path("rgb/a.png"));
  expectThrowContaining([&] { seq.load(0, 5000.0); }, "expected colour");
  writeRgb("a", CV_8UC4);
  const RgbdImages images = seq.load(0, 5000.0);
  EXPECT_EQ(images.rgb.type(), CV_8UC3);
}

TEST_F(TumFolderTest, SizeMismatchThrows) {
  writeStandardFolder();
  writeDepth("x", CV_16UC1, {10, 6});
  TumSequence seq(dir_.string(), 0.025);
  expectThrowContaining([&] { seq.load(0, 5000.0); }, path("depth/x.png") + ": size mismatch");
}

// Real data: the shared TUM fr1_xyz excerpt (../shared, never in the repository).
TEST(TumSequenceRealData, Freiburg1Xyz) {
  const std::string dir = test::sharedPath("data/tum/rgbd_dataset_freiburg1_xyz_37");
  PLY_SLAM_REQUIRE_SHARED(dir);

  size_t association_lines = 0;
  {
    std::ifstream in(dir + "/associations.txt");
    ASSERT_TRUE(in) << dir << "/associations.txt";
    for (std::string line; std::getline(in, line);) {
      if (!line.empty() && line[0] != '#') ++association_lines;
    }
  }
  TumSequence seq(dir);
  EXPECT_TRUE(seq.usedAssociationsFile());
  ASSERT_EQ(seq.size(), association_lines);
  EXPECT_TRUE(seq.hasGroundTruth());
  EXPECT_GT(seq.groundTruth().size(), 100u);

  for (size_t i : {size_t{0}, seq.size() - 1}) {
    const RgbdImages images = seq.load(i, 5000.0);
    EXPECT_EQ(images.rgb.cols, 640);
    EXPECT_EQ(images.rgb.rows, 480);
    EXPECT_EQ(images.rgb.type(), CV_8UC3);
    ASSERT_EQ(images.depth.type(), CV_32FC1);
    std::vector<float> valid;
    for (auto it = images.depth.begin<float>(); it != images.depth.end<float>(); ++it) {
      if (*it > 0.0f) valid.push_back(*it);
    }
    ASSERT_GT(valid.size(), 640u * 480u / 2) << "fewer than half the pixels have depth";
    std::nth_element(valid.begin(), valid.begin() + valid.size() / 2, valid.end());
    const float median = valid[valid.size() / 2];
    EXPECT_GT(median, 0.5f);
    EXPECT_LT(median, 3.0f);
  }

  // The nearest-stamp pairing (no associations.txt) keeps all 37 rgb frames of this excerpt.
  // Checked on a copy of the lists so that the shared folder stays read-only.
  const fs::path copy =
      fs::temp_directory_path() / ("ply_slam_test_tum_real_" + std::to_string(::getpid()));
  fs::remove_all(copy);
  fs::create_directories(copy);
  fs::copy_file(dir + "/rgb.txt", copy / "rgb.txt");
  fs::copy_file(dir + "/depth.txt", copy / "depth.txt");
  TumSequence nearest(copy.string());
  size_t rgb_lines = 0;
  {
    std::ifstream in(dir + "/rgb.txt");
    for (std::string line; std::getline(in, line);) {
      if (!line.empty() && line[0] != '#') ++rgb_lines;
    }
  }
  EXPECT_EQ(nearest.size() + nearest.unassociatedRgbFrames(), rgb_lines);
  EXPECT_GE(nearest.size(), association_lines);
  fs::remove_all(copy);
}

}  // namespace
}  // namespace ply_slam
