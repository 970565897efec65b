// WorldInMapFile: the map frame's placement saved beside a map, read back exactly, and refused
// with the file named when it is not one pose.
#include <gtest/gtest.h>

#include <fstream>

#include "ply_slam/map/world_in_map_file.h"
#include "temp_dir.h"

namespace ply_slam {
namespace {

std::string written(const TempDir& dir, const std::string& text) {
  const std::string path = (dir.path() / "world_in_map.txt").string();
  std::ofstream(path) << text;
  return path;
}

TEST(WorldInMapFile, RoundTripsAPose) {
  TempDir dir;
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(0.5, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(1.0, -2.0, 0.25);
  const std::string path = (dir.path() / WorldInMapFile::kName).string();
  WorldInMapFile::write(path, T);
  const std::optional<Eigen::Isometry3d> back = WorldInMapFile::read(path);
  ASSERT_TRUE(back);
  EXPECT_LT((back->matrix() - T.matrix()).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(WorldInMapFile, NoFileIsNoPlacement) {
  TempDir dir;
  EXPECT_FALSE(WorldInMapFile::read((dir.path() / "absent.txt").string()));
}

TEST(WorldInMapFile, RefusesWhatIsNotOnePoseNamingTheFile) {
  TempDir dir;
  for (const char* text : {"", "# only a comment\n", "1 2 3 0 0 0\n", "1 2 nan 0 0 0 1\n",
                           "1 2 3 0 0 0 2\n", "x y z qx qy qz qw\n"}) {
    const std::string path = written(dir, text);
    try {
      WorldInMapFile::read(path);
      ADD_FAILURE() << "accepted: " << text;
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace ply_slam
