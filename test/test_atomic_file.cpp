// Outputs are written to a temporary file and renamed into place (AtomicFile): a failed
// write throws an error naming the file and leaves the old file, never a truncated one.
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/stat.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "ply_slam/io/atomic_file.h"
#include "temp_dir.h"

namespace ply_slam {
namespace {

namespace fs = std::filesystem;

std::string readAll(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Only the files the test made: no temporary file left behind.
size_t filesIn(const fs::path& dir) {
  size_t n = 0;
  for (const auto& entry : fs::directory_iterator(dir)) n += !entry.is_directory();
  return n;
}

// EXPECT that `write` throws a message naming `path`.
template <typename Write>
void expectFailureNaming(const std::string& path, Write write) {
  try {
    write();
    ADD_FAILURE() << "no error for " << path;
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
}

TEST(AtomicFile, WritesTheFileAndLeavesNoTemporaryFile) {
  TempDir dir;
  const std::string path = dir.file("summary.json");
  writeTextFileAtomically(path, "old");
  writeTextFileAtomically(path, "{\"frames\": 3}\n");
  EXPECT_EQ(readAll(path), "{\"frames\": 3}\n");
  EXPECT_EQ(filesIn(dir.path()), 1u);
}

TEST(AtomicFile, AFolderThatIsAFileIsAnErrorNamingTheFile) {
  TempDir dir;
  writeTextFileAtomically(dir.file("out"), "a file, not a folder");
  const std::string path = dir.file("out/timing.csv");
  expectFailureNaming(path, [&] { writeTextFileAtomically(path, "frame\n"); });
}

TEST(AtomicFile, ADirectoryInTheWayIsAnErrorNamingIt) {
  TempDir dir;
  const std::string path = dir.file("summary.json");
  fs::create_directory(path);
  expectFailureNaming(path, [&] { writeTextFileAtomically(path, "{}\n"); });
  EXPECT_TRUE(fs::is_directory(path));
}

TEST(AtomicFile, ALinkToADeviceIsRefusedAndTheDeviceUntouched) {
  if (!fs::exists("/dev/full")) GTEST_SKIP() << "no /dev/full";
  TempDir dir;
  const std::string path = dir.file("dense_map.ply");
  fs::create_symlink("/dev/full", path);
  expectFailureNaming(path, [&] { writeTextFileAtomically(path, "ply\n"); });
  expectFailureNaming(path, [&] {
    writeFileAtomically(path, [](const std::string& temp) { return bool(std::ofstream(temp)); });
  });
  EXPECT_TRUE(fs::is_character_file("/dev/full"));
  EXPECT_TRUE(fs::is_symlink(path));
}

TEST(AtomicFile, ALinkToAFileUpdatesTheTargetAndStaysALink) {
  TempDir dir;
  writeTextFileAtomically(dir.file("target.txt"), "old");
  fs::create_symlink(dir.file("target.txt"), dir.file("link.txt"));
  writeTextFileAtomically(dir.file("link.txt"), "new");
  EXPECT_TRUE(fs::is_symlink(dir.file("link.txt")));
  EXPECT_EQ(readAll(dir.file("target.txt")), "new");
}

// A full disk, made with a file-size limit: the write fails part-way (EFBIG, as ENOSPC would).
TEST(AtomicFile, AFullDiskIsAnErrorAndKeepsTheOldFile) {
  TempDir dir;
  const std::string path = dir.file("timing.csv");
  writeTextFileAtomically(path, "old");
  rlimit saved{};
  getrlimit(RLIMIT_FSIZE, &saved);
  const auto old_handler = std::signal(SIGXFSZ, SIG_IGN);
  rlimit small = saved;
  small.rlim_cur = 4096;
  setrlimit(RLIMIT_FSIZE, &small);
  expectFailureNaming(path, [&] {
    AtomicFile file(path);
    for (int i = 0; i < 100000; ++i) file.stream() << "1,2,3,4,5,6,7,8\n";
    file.commit();
  });
  setrlimit(RLIMIT_FSIZE, &saved);
  std::signal(SIGXFSZ, old_handler);
  EXPECT_EQ(readAll(path), "old");
  EXPECT_EQ(filesIn(dir.path()), 1u);
}

TEST(AtomicFile, AWriterThatFailsLeavesTheOldFile) {
  TempDir dir;
  const std::string path = dir.file("map_top.png");
  writeTextFileAtomically(path, "old");
  expectFailureNaming(path, [&] {
    writeFileAtomically(path, [](const std::string& temp) {
      std::ofstream(temp) << "half";
      return false;
    });
  });
  expectFailureNaming(path, [&] {
    writeFileAtomically(
        path, [](const std::string&) -> bool { throw std::runtime_error("encoder failed"); });
  });
  EXPECT_EQ(readAll(path), "old");
  EXPECT_EQ(filesIn(dir.path()), 1u);
}

TEST(AtomicFile, AnUncommittedFileLeavesNothing) {
  TempDir dir;
  {
    AtomicFile file(dir.file("summary.json"));
    file.stream() << "{";
  }
  EXPECT_EQ(filesIn(dir.path()), 0u);
}

TEST(AtomicFile, TheTemporaryFileKeepsTheExtension) {
  TempDir dir;
  std::string seen;
  writeFileAtomically(dir.file("map_top.png"), [&](const std::string& temp) {
    seen = temp;
    return bool(std::ofstream(temp) << "x");
  });
  EXPECT_EQ(fs::path(seen).extension(), ".png");
  EXPECT_EQ(fs::path(seen).parent_path(), dir.path());
}

}  // namespace
}  // namespace ply_slam
