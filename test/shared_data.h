#pragma once

// Where tests find ../shared (data and models, never in the repository): $PLY_SLAM_SHARED,
// else the folder beside the source tree.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <string>

namespace ply_slam::test {

inline std::string sharedDir() {
  const char* env = std::getenv("PLY_SLAM_SHARED");
  if (env && *env) return env;
  // The source dir may be the catkin workspace's symlink: resolve it before going up.
  return (std::filesystem::weakly_canonical(PLY_SLAM_SOURCE_DIR).parent_path() / "shared").string();
}

inline std::string sharedPath(const std::string& relative) { return sharedDir() + "/" + relative; }

inline bool underCi() {
  const char* ci = std::getenv("CI");
  return ci && std::string(ci) == "true";
}

}  // namespace ply_slam::test

// Skips the test when `path` is missing, with a message; fails instead under CI=true.
#define PLY_SLAM_REQUIRE_SHARED(path)                                                              \
  do {                                                                                             \
    if (!std::filesystem::exists(path)) {                                                          \
      if (::ply_slam::test::underCi()) FAIL() << "CI=true but shared data is missing: " << (path); \
      GTEST_SKIP() << "shared data missing: " << (path)                                            \
                   << " (set PLY_SLAM_SHARED to the folder holding data/ and models/)";            \
    }                                                                                              \
  } while (0)
