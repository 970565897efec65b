// The tools as a user runs them: --help and unknown options, and the bad inputs of a hostile
// user (a folder as the config, options that do nothing, a ground truth that does not fit the
// run, outputs that cannot be written, duplicate and huge poses for ply_slam_eval).
#include <fcntl.h>
#include <gtest/gtest.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "shared_data.h"
#include "temp_dir.h"

namespace ply_slam {
namespace {

namespace fs = std::filesystem;

const std::vector<std::string> kTools = {
    "ply_slam_eval",        "ply_slam_lines",         "ply_slam_loops",
    "ply_slam_map_compare", "ply_slam_rgbd_odometry", "ply_slam_segment",
    "ply_slam_synth",       "ply_slam_tum",           "ply_slam_vocabulary"};

std::string readAll(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

struct Result {
  int exit_code = -1;
  std::string out, err;
};

// Runs TOOL with `arguments` (already quoted where needed) in `dir`.
Result run(const TempDir& dir, const std::string& tool, const std::string& arguments) {
  const std::string command = "cd '" + dir.path().string() + "' && '" PLY_SLAM_TOOL_DIR "/" + tool +
                              "' " + arguments + " >stdout.txt 2>stderr.txt";
  const int status = std::system(command.c_str());
  Result r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  r.out = readAll(dir.path() / "stdout.txt");
  r.err = readAll(dir.path() / "stderr.txt");
  return r;
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

void writeText(const fs::path& path, const std::string& text) { std::ofstream(path) << text; }

TEST(ToolsCommandLine, EveryToolPrintsItsUsageForHelp) {
  TempDir dir;
  for (const auto& tool : kTools) {
    const Result r = run(dir, tool, "--help");
    EXPECT_EQ(r.exit_code, 0) << tool << ": " << r.err;
    EXPECT_TRUE(contains(r.out, "usage: " + tool)) << tool << " printed: " << r.out;
  }
}

TEST(ToolsCommandLine, EveryToolNamesAnUnknownOption) {
  TempDir dir;
  for (const auto& tool : kTools)
    for (const std::string option : {"--bogus", "--no-line"}) {
      const std::string arguments = tool == "ply_slam_eval" ? "ate " + option : option;
      const Result r = run(dir, tool, arguments);
      EXPECT_NE(r.exit_code, 0) << tool;
      EXPECT_TRUE(contains(r.err, "unknown option " + option)) << tool << " said: " << r.err;
    }
}

// A usage error, wherever a tool finds it, exits 2 with the usage after the message.
TEST(ToolsCommandLine, EveryToolExitsTwoWithItsUsageOnAUsageError) {
  TempDir dir;
  for (const auto& tool : kTools) {
    const std::string arguments = tool == "ply_slam_eval" ? "ate --bogus" : "--bogus";
    const Result r = run(dir, tool, arguments);
    EXPECT_EQ(r.exit_code, 2) << tool << " said: " << r.err;
    EXPECT_TRUE(contains(r.err, tool + ": unknown option --bogus")) << tool << ": " << r.err;
    EXPECT_TRUE(contains(r.err, "usage: " + tool)) << tool << " said: " << r.err;
  }
}

// --segment-lag models --live's masks: it needs a segmenter, not --live, and a lag >= 1.
TEST(ToolsCommandLine, SegmentLagWithoutASegmenterOrWithLiveIsAUsageError) {
  TempDir dir;
  const std::string base = "--sequence s --config c --out o ";
  for (const std::string& extra :
       {std::string("--segment-lag 4"), std::string("--segmenter masks --live --segment-lag 4"),
        std::string("--segmenter masks --segment-lag 0")}) {
    const Result r = run(dir, "ply_slam_tum", base + extra);
    EXPECT_EQ(r.exit_code, 2) << extra << " said: " << r.err;
    EXPECT_TRUE(contains(r.err, "--segment-lag")) << extra << " said: " << r.err;
  }
}

// Issue #53: --max-frames 0 ran no frame and --sequence given twice took the last silently.
TEST(ToolsCommandLine, NoFramesAndAnOptionGivenTwiceAreUsageErrors) {
  TempDir dir;
  const std::string base = "--sequence s --config c --out o ";
  for (const std::string& extra : {std::string("--max-frames 0"), std::string("--sequence t")}) {
    const Result r = run(dir, "ply_slam_tum", base + extra);
    EXPECT_EQ(r.exit_code, 2) << extra << " said: " << r.err;
    EXPECT_TRUE(contains(r.err, extra.substr(0, extra.find(' ')))) << extra << " said: " << r.err;
  }
  EXPECT_TRUE(
      contains(run(dir, "ply_slam_tum", base + "--sequence t").err, "--sequence is given twice"));
}

// Each tool's main goes through CommandLine and runTool (one behaviour for --help, unknown
// options, usage errors and failures).
TEST(ToolsCommandLine, EveryToolParsesWithCommandLine) {
  for (const auto& tool : kTools) {
    const std::string source =
        readAll(fs::path(PLY_SLAM_SOURCE_DIR) / "src" / "tools" / (tool + ".cpp"));
    EXPECT_TRUE(contains(source, "CommandLine line;")) << tool;
    EXPECT_TRUE(contains(source, "runTool(\"" + tool + "\"")) << tool;
  }
}

const std::string kSequence = "data/tum/rgbd_dataset_freiburg1_xyz_37";

std::string quoted(const std::string& text) { return "'" + text + "'"; }

std::string tumArguments(const std::string& sequence, const std::string& out) {
  return "--sequence " + quoted(sequence) + " --config " +
         quoted(std::string(PLY_SLAM_SOURCE_DIR) + "/config/tum_fr1.yaml") + " --out " +
         quoted(out) + " --no-loop";
}

TEST(ToolsCommandLine, AFolderAsConfigAndAModelWithoutYoloAreErrors) {
  TempDir dir;
  const std::string sequence = test::sharedPath(kSequence);
  Result r = run(
      dir, "ply_slam_tum",
      "--sequence " + quoted(sequence) + " --config " + quoted(dir.path().string()) + " --out out");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_TRUE(contains(r.err, dir.path().string()) && contains(r.err, "directory")) << r.err;
  r = run(dir, "ply_slam_tum", tumArguments(sequence, "out") + " --model m.onnx");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(contains(r.err, "--segmenter yolo")) << r.err;
  r = run(dir, "ply_slam_loops",
          "--sequence " + quoted(sequence) + " --config " + quoted(dir.path().string()) +
              " --out out --input 320x320");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_TRUE(contains(r.err, "--segmenter yolo")) << r.err;
}

// The false-loop bounds of ply_slam_loops lie at or beyond the true ones: a band of negative
// width would make a pair true and false at once.
TEST(ToolsCommandLine, LoopsFalseBoundsBelowTheTrueOnesAreRefused) {
  TempDir dir;
  const std::string args = "--sequence " + quoted(test::sharedPath(kSequence)) + " --config " +
                           quoted(std::string(PLY_SLAM_SOURCE_DIR) + "/config/tum_fr1.yaml") +
                           " --out out";
  for (const std::string& bad : {"--false-distance-m 0.2", "--false-angle-deg 10",
                                 "--false-distance-m nan", "--false-angle-deg x"}) {
    const Result r = run(dir, "ply_slam_loops", args + " " + bad);
    EXPECT_EQ(r.exit_code, 2) << bad << ": " << r.err;
    EXPECT_TRUE(contains(r.err, bad.substr(0, bad.find(' '))) && contains(r.err, ">="))
        << bad << ": " << r.err;
  }
  EXPECT_FALSE(fs::exists(dir.path() / "out"));
}

TEST(ToolsCommandLine, GapsNeedAFrameBeforeAndAfterThem) {
  TempDir dir;
  const std::string args = tumArguments(test::sharedPath(kSequence), "out");
  for (const std::string& bad :
       {"--kidnap 5", "--kidnap 0:3", "--cover 9:9", "--cover x:4", "--kidnap 2:4 --cover 6:8"}) {
    const Result r = run(dir, "ply_slam_tum", args + " " + bad);
    EXPECT_EQ(r.exit_code, 2) << bad << ": " << r.err;
    EXPECT_TRUE(contains(r.err, "--kidnap") || contains(r.err, "--cover")) << bad << ": " << r.err;
  }
  // fr1_xyz_37 has 37 frames: a gap up to the last leaves nothing to relocalise in.
  const Result r = run(dir, "ply_slam_tum", args + " --kidnap 10:37");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_TRUE(contains(r.err, "nothing left after it")) << r.err;
}

// Two passes of one place, the same stamps, different paths; each run's poses in the map's
// frame, which is the first pass's ground-truth frame turned by 90 degrees about z and moved
// (x, y) -> (-y + 1, x). A TUM line per pose: stamp x y z and the identity quaternion.
std::string passOf(double phase, bool in_map_frame) {
  std::ostringstream text;
  for (int k = 0; k < 40; ++k) {
    const double x = std::cos(0.1 * k + phase), y = std::sin(0.13 * k + 2 * phase), z = 0.02 * k;
    text << 100 + k * 0.1 << ' ' << (in_map_frame ? -y + 1 : x) << ' ' << (in_map_frame ? x : y)
         << ' ' << z << " 0 0 " << (in_map_frame ? "0.7071067811865476 0.7071067811865476" : "0 1")
         << '\n';
  }
  return text.str();
}

// ply_slam_eval ate --align-with: the second pass, localised in the first pass's map, is judged
// with the map run's alignment; with its own ground truth associated to the map run's poses
// (the same stamps, other places) that alignment is wrong, with --align-truth it is right.
TEST(ToolsCommandLine, EvalAlignsAnotherPassWithTheMapRunsOwnGroundTruth) {
  TempDir dir;
  writeText(dir.path() / "gt1.txt", passOf(0.0, false));
  writeText(dir.path() / "map_run.txt", passOf(0.0, true));
  writeText(dir.path() / "gt2.txt", passOf(0.7, false));
  writeText(dir.path() / "pass2.txt", passOf(0.7, true));
  const auto rmse = [](const std::string& json) {
    return nlohmann::json::parse(json).at("rmse").get<double>();
  };
  Result r = run(dir, "ply_slam_eval",
                 "ate gt2.txt pass2.txt --json --align-with map_run.txt --align-truth gt1.txt");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_LT(rmse(r.out), 1e-4) << r.out;  // the files' 6 digits
  r = run(dir, "ply_slam_eval", "ate gt2.txt pass2.txt --json --align-with map_run.txt");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_GT(rmse(r.out), 0.1) << r.out;
  r = run(dir, "ply_slam_eval", "ate gt2.txt pass2.txt --align-truth gt1.txt");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(contains(r.err, "--align-truth needs --align-with")) << r.err;
}

// The sequence's images with a ground truth 1000 s later: nothing to pair with.
std::string sequenceWithLateGroundTruth(const TempDir& dir) {
  const fs::path source = test::sharedPath(kSequence);
  const fs::path copy = dir.path() / "late_gt";
  fs::create_directory(copy);
  for (const char* name : {"rgb", "depth", "rgb.txt", "depth.txt", "associations.txt"})
    fs::create_symlink(source / name, copy / name);
  std::ifstream in(source / "groundtruth.txt");
  std::ofstream out(copy / "groundtruth.txt");
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    double stamp;
    fields >> stamp;
    std::string rest;
    std::getline(fields, rest);
    out << std::fixed << stamp + 1000.0 << rest << '\n';
  }
  return copy.string();
}

TEST(ToolsCommandLine, AGroundTruthThatDoesNotFitStillGivesEveryOutput) {
  PLY_SLAM_REQUIRE_SHARED(test::sharedPath(kSequence));
  TempDir dir;
  const std::string sequence = sequenceWithLateGroundTruth(dir);
  const Result r = run(dir, "ply_slam_tum", tumArguments(sequence, "out"));
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_TRUE(contains(r.err, "groundtruth.txt")) << r.err;
  for (const char* name : {"CameraTrajectory.txt", "KeyFrameTrajectory.txt", "timing.csv",
                           "summary.json", "trajectory.png", "semantic_octree.ot", "octree.bt",
                           "map_legend.txt", "map_top.png", "dense_map.pcd", "dense_map.ply"})
    EXPECT_TRUE(fs::exists(dir.path() / "out" / name)) << name;
  const std::string summary = readAll(dir.path() / "out" / "summary.json");
  EXPECT_TRUE(contains(summary, "\"evaluation_error\"")) << summary;
  EXPECT_TRUE(contains(summary, sequence + "/groundtruth.txt")) << summary;
  EXPECT_FALSE(contains(summary, "\"ate\"")) << summary;
}

TEST(ToolsCommandLine, AnOutputThatCannotBeWrittenIsNamedAndFailsTheRun) {
  PLY_SLAM_REQUIRE_SHARED(test::sharedPath(kSequence));
  TempDir dir;
  fs::create_directories(dir.path() / "out" / "summary.json");
  if (fs::exists("/dev/full")) fs::create_symlink("/dev/full", dir.path() / "out" / "timing.csv");
  const Result r = run(dir, "ply_slam_tum",
                       tumArguments(test::sharedPath(kSequence), "out") + " --max-frames 8");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_TRUE(contains(r.err, "out/summary.json")) << r.err;
  if (fs::exists("/dev/full")) {
    EXPECT_TRUE(contains(r.err, "out/timing.csv")) << r.err;
    // The count is of files, and the last line names exactly those (issue #53).
    EXPECT_TRUE(contains(r.err, "2 output(s) not written: out/timing.csv and out/summary.json"))
        << r.err;
  }
  EXPECT_TRUE(fs::exists(dir.path() / "out" / "CameraTrajectory.txt"));
}

// A second run into the same folder that writes no dense cloud left the first run's beside
// its own outputs (issue #53); a link there is the user's and stays.
TEST(ToolsCommandLine, OutputsOfAnEarlierRunAreRemoved) {
  PLY_SLAM_REQUIRE_SHARED(test::sharedPath(kSequence));
  TempDir dir;
  const std::string sequence = test::sharedPath(kSequence);
  Result r = run(dir, "ply_slam_tum", tumArguments(sequence, "st") + " --max-frames 12");
  ASSERT_TRUE(fs::exists(dir.path() / "st" / "dense_map.ply")) << r.err;
  writeText(dir.path() / "kept.txt", "the user's");
  fs::remove(dir.path() / "st" / "map.pgm");
  fs::create_symlink(dir.path() / "kept.txt", dir.path() / "st" / "map.pgm");
  r = run(dir, "ply_slam_tum", tumArguments(sequence, "st") + " --max-frames 2");
  EXPECT_TRUE(contains(r.out, "of an earlier run from st: ")) << r.out;
  EXPECT_TRUE(contains(r.out, " dense_map.pcd dense_map.ply")) << r.out;
  EXPECT_FALSE(fs::exists(dir.path() / "st" / "dense_map.pcd"));
  EXPECT_FALSE(fs::exists(dir.path() / "st" / "dense_map.ply"));
  EXPECT_TRUE(fs::is_symlink(dir.path() / "st" / "map.pgm"));
  EXPECT_TRUE(fs::exists(dir.path() / "st" / "summary.json"));
}

TEST(ToolsCommandLine, AMapWithoutDenseCloudSaysSo) {
  PLY_SLAM_REQUIRE_SHARED(test::sharedPath(kSequence));
  TempDir dir;
  const Result r = run(dir, "ply_slam_tum",
                       tumArguments(test::sharedPath(kSequence), "out") + " --max-frames 2");
  EXPECT_TRUE(contains(r.err, "dense_map.pcd and dense_map.ply not written")) << r.err;
  const std::string summary = readAll(dir.path() / "out" / "summary.json");
  EXPECT_TRUE(contains(summary, "\"files_left_out\"")) << summary;
  // Two frames cannot be evaluated against the ground truth (ATE needs three): said too.
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_TRUE(contains(summary, "only 2 tracked frames")) << summary;
}

// The process's own high-water mark (MiB), from wait4: the figure summary.json must give.
double runForPeakRssMb(const std::vector<std::string>& arguments, const fs::path& log) {
  std::vector<char*> argv;
  for (const auto& a : arguments) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, 1, 2);
  pid_t pid = 0;
  const int spawned = posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (spawned != 0) return -1.0;
  int status = 0;
  rusage usage{};
  wait4(pid, &status, 0, &usage);
  return WIFEXITED(status) && WEXITSTATUS(status) == 0 ? usage.ru_maxrss / 1024.0 : -1.0;
}

// gcc says __SANITIZE_ADDRESS__, clang __has_feature(address_sanitizer).
#if defined(__SANITIZE_ADDRESS__)
#define PLY_SLAM_UNDER_ASAN
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define PLY_SLAM_UNDER_ASAN
#endif
#endif

// peak_rss_mb was taken before the dense maps were finished: 186 MiB reported, 214 MiB used.
TEST(ToolsCommandLine, PeakRssIsTheWholeRunsHighWaterMark) {
#ifdef PLY_SLAM_UNDER_ASAN
  GTEST_SKIP() << "AddressSanitizer's leak check at exit raises the high-water mark after the tool "
                  "has reported it (718 vs 816 MiB measured)";
#endif
  const std::string sequence = test::sharedPath("data/tum/rgbd_dataset_freiburg1_rpy_150_349");
  PLY_SLAM_REQUIRE_SHARED(sequence);
  TempDir dir;
  const double measured =
      runForPeakRssMb({PLY_SLAM_TOOL_DIR "/ply_slam_tum", "--sequence", sequence, "--config",
                       std::string(PLY_SLAM_SOURCE_DIR) + "/config/tum_fr1.yaml", "--out",
                       (dir.path() / "out").string(), "--no-loop"},
                      dir.path() / "log.txt");
  ASSERT_GT(measured, 0.0) << readAll(dir.path() / "log.txt");
  const nlohmann::json summary =
      nlohmann::json::parse(readAll(dir.path() / "out" / "summary.json"));
  ASSERT_TRUE(summary.contains("peak_rss_mb")) << summary;
  const double reported = summary["peak_rss_mb"].get<double>();
  EXPECT_NEAR(reported, measured, 0.02 * measured) << "reported " << reported << " MiB";
}

// --save-map writes a map that --map loads; a missing map and --localisation-only alone are
// errors that say so.
TEST(ToolsCommandLine, ASavedMapLoadsAgain) {
  PLY_SLAM_REQUIRE_SHARED(test::sharedPath(kSequence));
  TempDir dir;
  const std::string sequence = test::sharedPath(kSequence);
  Result r = run(dir, "ply_slam_tum",
                 tumArguments(sequence, "mapped") + " --max-frames 10 --save-map saved");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir.path() / "saved" / "map.plymap"));
  EXPECT_TRUE(contains(readAll(dir.path() / "mapped" / "summary.json"), "\"saved\""));
  r = run(dir, "ply_slam_tum", tumArguments(sequence, "loaded") + " --max-frames 12 --map saved");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json summary =
      nlohmann::json::parse(readAll(dir.path() / "loaded" / "summary.json"));
  EXPECT_EQ(summary["map"]["first_tracked_frame"], 0) << summary;
  r = run(dir, "ply_slam_tum", tumArguments(sequence, "none") + " --map nowhere");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_TRUE(contains(r.err, "nowhere/map.plymap") && contains(r.err, "cannot be opened"))
      << r.err;
  r = run(dir, "ply_slam_tum", tumArguments(sequence, "none") + " --localisation-only false");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(contains(r.err, "--localisation-only needs --map")) << r.err;
}

// A trainer that saw no descriptors replaced a good 3.4 MB vocabulary by a one-word file and
// exited 0 (issue #53): now it fails and leaves the file as it was.
TEST(ToolsCommandLine, AVocabularyFromNoDescriptorsFailsAndKeepsTheOldFile) {
  TempDir dir;
  const std::string old = "a vocabulary that must stay";
  writeText(dir.path() / "good.voc", old);
  writeText(dir.path() / "list.txt", "nonexistent.png\n");
  fs::create_directory(dir.path() / "junk");
  writeText(dir.path() / "junk" / "a.png", "not a png");
  writeText(dir.path() / "junk" / "b.png", "");
  for (const char* images : {"list.txt", "junk"}) {
    const Result r = run(dir, "ply_slam_vocabulary",
                         std::string("--images ") + images + " --kind orb --out good.voc");
    EXPECT_EQ(r.exit_code, 1) << images << ": " << r.err;
    EXPECT_TRUE(contains(r.err, "gave 0 descriptors") && contains(r.err, "good.voc not written"))
        << r.err;
    EXPECT_EQ(readAll(dir.path() / "good.voc"), old) << images;
  }
}

const char* const kGroundTruth =
    "1.00 0 0 0 0 0 0 1\n1.10 1 0 0 0 0 0 1\n1.20 2 0 0 0 0 0 1\n1.30 3 0 0 0 0 0 1\n";

TEST(ToolsCommandLine, EvalRefusesAStampGivenTwice) {
  TempDir dir;
  writeText(dir.path() / "gt.txt", kGroundTruth);
  writeText(dir.path() / "est.txt",
            "1.00 0 0 0 0 0 0 1\n1.10 1 0 0 0 0 0 1\n1.10 1 0 0 0 0 0 1\n1.30 3 0 0 0 0 0 1\n");
  const Result r = run(dir, "ply_slam_eval", "ate gt.txt est.txt --json");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_TRUE(contains(r.err, "est.txt") && contains(r.err, "twice")) << r.err;
}

TEST(ToolsCommandLine, EvalNeverPrintsNanForHugeCoordinates) {
  TempDir dir;
  writeText(dir.path() / "gt.txt", kGroundTruth);
  writeText(dir.path() / "est.txt",
            "1.00 1e308 0 0 0 0 0 1\n1.10 -1e308 0 0 0 0 0 1\n1.20 1e308 0 0 0 0 0 1\n"
            "1.30 -1e308 0 0 0 0 0 1\n");
  for (const char* command : {"ate", "rpe"}) {
    const Result r = run(dir, "ply_slam_eval", std::string(command) + " gt.txt est.txt --json");
    EXPECT_EQ(r.exit_code, 1) << command << ": " << r.out;
    EXPECT_FALSE(contains(r.out, "nan") || contains(r.out, "inf")) << r.out;
    EXPECT_TRUE(contains(r.err, "est.txt") && contains(r.err, "line 1")) << r.err;
  }
}

}  // namespace
}  // namespace ply_slam
