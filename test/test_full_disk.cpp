// Every writer on a full disk: PCL's and OpenCV's writers report success when their writes
// fail (a 45 kB dense_map.ply whose header announced 7 262 points, a 0-byte map.pgm, both
// unnamed, issue #53). A full disk is made with a file-size limit: the writes fail part-way
// (EFBIG), as ENOSPC would. Each file must then be named, and the old one kept.
#include <gtest/gtest.h>
#include <pcl/io/pcd_io.h>
#include <pcl/io/ply_io.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <sys/resource.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <functional>
#include <opencv2/imgcodecs.hpp>
#include <sstream>
#include <string>

#include "ply_slam/dense/cloud_files.h"
#include "ply_slam/dense/grid_map_files.h"
#include "ply_slam/dense/occupancy_grid.h"
#include "ply_slam/io/file_writes.h"
#include "ply_slam/io/image_file.h"
#include "temp_dir.h"

namespace ply_slam {
namespace {

namespace fs = std::filesystem;

std::string readAll(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Runs `write` with files limited to `bytes`, SIGXFSZ ignored.
void withFullDisk(size_t bytes, const std::function<void()>& write) {
  rlimit saved{};
  getrlimit(RLIMIT_FSIZE, &saved);
  const auto old_handler = std::signal(SIGXFSZ, SIG_IGN);
  rlimit small = saved;
  small.rlim_cur = bytes;
  setrlimit(RLIMIT_FSIZE, &small);
  write();
  setrlimit(RLIMIT_FSIZE, &saved);
  std::signal(SIGXFSZ, old_handler);
}

DenseCloud cloudOf(int points) {
  DenseCloud cloud;
  for (int i = 0; i < points; ++i) {
    pcl::PointXYZRGBL p;
    p.x = 0.01f * i, p.y = 1.0f, p.z = 2.0f;
    p.r = 10, p.g = 20, p.b = 30, p.label = 3;
    cloud.push_back(p);
  }
  cloud.width = cloud.size();
  cloud.height = 1;
  return cloud;
}

// `write` into a 20 kB "disk" fails naming `path`, and the old content stays.
void expectNamedAndOldKept(const fs::path& path, const std::function<void()>& write) {
  std::ofstream(path) << "old";
  bool threw = false;
  withFullDisk(20000, [&] {
    try {
      write();
    } catch (const FileWriteError& e) {
      threw = true;
      EXPECT_EQ(e.path(), path.string());
      EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
    }
  });
  EXPECT_TRUE(threw) << path << " reported as written";
  EXPECT_EQ(readAll(path), "old") << path;
  size_t files = 0;
  for (const auto& entry : fs::directory_iterator(path.parent_path()))
    files += !entry.is_directory();
  EXPECT_EQ(files, 1u) << "a temporary file left beside " << path;
}

TEST(FullDisk, DenseCloudsAreNamedAndTheOldFilesKept) {
  const DenseCloud cloud = cloudOf(7262);
  TempDir ply_dir, pcd_dir;
  expectNamedAndOldKept(ply_dir.path() / "dense_map.ply",
                        [&] { writeCloudPly(ply_dir.file("dense_map.ply"), cloud); });
  expectNamedAndOldKept(pcd_dir.path() / "dense_map.pcd",
                        [&] { writeCloudPcd(pcd_dir.file("dense_map.pcd"), cloud); });
}

TEST(FullDisk, ImagesAreNamedAndTheOldFilesKept) {
  cv::Mat noise(400, 400, CV_8UC3);
  cv::randu(noise, 0, 255);  // does not compress below the limit
  for (const char* name : {"map_top.png", "map.pgm", "frame.jpg"}) {
    TempDir dir;
    cv::Mat image = std::string(name) == "map.pgm" ? cv::Mat(400, 400, CV_8UC1, 205) : noise;
    expectNamedAndOldKept(dir.path() / name, [&] { writeImageFile(dir.file(name), image); });
  }
}

// What PCL and OpenCV wrote with room to spare reads back as it was written.
TEST(FullDisk, WithRoomTheFilesReadBack) {
  TempDir dir;
  const DenseCloud cloud = cloudOf(100);
  writeCloudPcd(dir.file("a.pcd"), cloud);
  writeCloudPly(dir.file("a.ply"), cloud);
  DenseCloud pcd, ply;
  ASSERT_EQ(pcl::io::loadPCDFile(dir.file("a.pcd"), pcd), 0);
  ASSERT_EQ(pcl::io::loadPLYFile(dir.file("a.ply"), ply), 0);
  ASSERT_EQ(pcd.size(), 100u);
  ASSERT_EQ(ply.size(), 100u);
  EXPECT_EQ(pcd[42].x, cloud[42].x);
  EXPECT_EQ(pcd[42].label, 3u);
  EXPECT_EQ(ply[42].g, 20);
  // The PCD bytes are PCL's own.
  pcl::io::savePCDFileBinary(dir.file("pcl.pcd"), cloud);
  EXPECT_EQ(readAll(dir.file("a.pcd")), readAll(dir.file("pcl.pcd")));
  const cv::Mat grey(30, 40, CV_8UC1, 7);
  writeImageFile(dir.file("g.pgm"), grey);
  EXPECT_EQ(cv::countNonZero(cv::imread(dir.file("g.pgm"), cv::IMREAD_UNCHANGED) != grey), 0);
}

// One attempt that writes two files counts and names both ("6 output(s) not written" named
// 8 before); map.yaml is still tried after map.pgm failed.
TEST(FullDisk, FileWritesCountsAndNamesEachFile) {
  TempDir dir;
  fs::create_directories(dir.path() / "map.pgm");
  fs::create_directories(dir.path() / "map.yaml");
  FileWrites outputs;
  FloorFrame floor;
  const OccupancyGrid grid(4, 3, 0.05, Eigen::Vector2d(0, 0), floor);
  EXPECT_FALSE(outputs.attempt([&] { writeGridMap(dir.path().string(), grid); }));
  EXPECT_FALSE(outputs.attempt([] { throw std::runtime_error("no file named"); }));
  ASSERT_EQ(outputs.failures().size(), 3u);
  EXPECT_EQ(outputs.namesText(),
            dir.file("map.pgm") + ", " + dir.file("map.yaml") + " and (no file named)");
  // save_map's reply and ply_slam_tum's last line.
  EXPECT_EQ(outputs.summaryText(), "3 output(s) not written: " + outputs.namesText());
  EXPECT_EQ(outputs.reasonsText().find("cannot write " + dir.file("map.pgm")), 0u);
}

}  // namespace
}  // namespace ply_slam
