// loadConfig: the shipped configs load with their documented values, and every kind of bad
// file is rejected with a ConfigError that names the file and the offending key.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

#include "ply_slam/system/system_config.h"

namespace ply_slam {
namespace {

namespace fs = std::filesystem;

const std::string kConfigDir = std::string(PLY_SLAM_SOURCE_DIR) + "/config/";

// A complete, valid config in the layout of the shipped files; tests edit one line of it.
const char* const kValidYaml = R"(camera:
  fx: 517.3
  fy: 516.5
  cx: 318.6
  cy: 255.3
  width: 640
  height: 480
  distortion: [0.2624, -0.9531, -0.0054, 0.0026, 1.1633]
  depth_factor: 5000.0
  min_depth: 0.3
  max_depth: 6.0
  depth_noise:
    alpha: 6.25e-6
    beta: 0.0
    gamma: 1.0e-6
orb:
  num_features: 1000
  num_levels: 8
  scale_factor: 1.2
tracking:
  search_radius_px: 15
  nn_ratio: 0.9
  max_point_depth: 6.0
)";

// Files under a per-process temporary directory, removed after each test.
class ConfigFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("ply_slam_test_config_" + std::to_string(::getpid()) + "_" + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string write(const std::string& name, const std::string& text) const {
    const std::string path = (dir_ / name).string();
    std::ofstream(path) << text;
    return path;
  }

  // kValidYaml with the first occurrence of `from` replaced by `to` (which must exist).
  std::string writeEdited(const std::string& name, const std::string& from,
                          const std::string& to) const {
    std::string text = kValidYaml;
    const size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << "test bug: '" << from << "' not in the template";
    if (at != std::string::npos) text.replace(at, from.size(), to);
    return write(name, text);
  }

  fs::path dir_;
};

// Loading `path` must throw ConfigError mentioning the path and every fragment.
void expectConfigError(const std::string& path, const std::vector<std::string>& fragments) {
  try {
    loadConfig(path);
    ADD_FAILURE() << path << " loaded, expected a ConfigError";
  } catch (const ConfigError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(path), std::string::npos)
        << "message '" << message << "' lacks the path " << path;
    for (const auto& fragment : fragments)
      EXPECT_NE(message.find(fragment), std::string::npos)
          << "message '" << message << "' lacks '" << fragment << "'";
  } catch (const std::exception& e) {
    ADD_FAILURE() << path << " threw a non-ConfigError: " << e.what();
  }
}

struct ShippedIntrinsics {
  const char* file;
  double fx, fy, cx, cy, depth_factor;
  bool distorted;
};

TEST(ShippedConfig, EveryFileLoadsWithItsDocumentedIntrinsics) {
  // TUM values from the benchmark's published calibration (DESIGN.md); D435i from its file.
  const ShippedIntrinsics expected[] = {
      {"tum_fr1.yaml", 517.3, 516.5, 318.6, 255.3, 5000.0, true},
      {"tum_fr2.yaml", 520.9, 521.0, 325.1, 249.7, 5000.0, true},
      {"tum_fr3.yaml", 535.4, 539.2, 320.1, 247.6, 5000.0, false},
      {"d435i.yaml", 615.0, 615.0, 320.0, 240.0, 1000.0, false},
      {"bonn.yaml", 542.822841, 542.576870, 315.593520, 237.756098, 5000.0, false},
  };
  // Every shipped file is covered: a new one must be added here.
  size_t yaml_files = 0;
  for (const auto& entry : fs::directory_iterator(kConfigDir)) {
    if (entry.path().extension() != ".yaml") continue;
    ++yaml_files;
    bool listed = false;
    for (const auto& e : expected) listed |= entry.path().filename() == e.file;
    EXPECT_TRUE(listed) << entry.path() << " is not checked by this test";
  }
  EXPECT_EQ(yaml_files, std::size(expected));

  for (const auto& e : expected) {
    SCOPED_TRACE(e.file);
    const std::string path = kConfigDir + e.file;
    SystemConfig config;
    ASSERT_NO_THROW(config = loadConfig(path));
    EXPECT_EQ(config.source_path, path);
    const PinholeCamera& c = config.camera;
    EXPECT_DOUBLE_EQ(c.fx, e.fx);
    EXPECT_DOUBLE_EQ(c.fy, e.fy);
    EXPECT_DOUBLE_EQ(c.cx, e.cx);
    EXPECT_DOUBLE_EQ(c.cy, e.cy);
    EXPECT_EQ(c.width, 640);
    EXPECT_EQ(c.height, 480);
    EXPECT_DOUBLE_EQ(c.depth_factor, e.depth_factor);
    EXPECT_EQ(c.hasDistortion(), e.distorted);
    EXPECT_LT(c.min_depth, c.max_depth);
    EXPECT_GT(c.depth_noise.variance(c.min_depth), 0.0);
    EXPECT_GT(config.orb.num_features, 0);
    EXPECT_GT(config.orb.scale_factor, 1.0);
  }
}

TEST(ShippedConfig, Fr1ValuesBeyondTheIntrinsics) {
  const SystemConfig config = loadConfig(kConfigDir + "tum_fr1.yaml");
  ASSERT_EQ(config.camera.distortion.total(), 5u);
  ASSERT_EQ(config.camera.distortion.type(), CV_64F);
  const double k[5] = {0.2624, -0.9531, -0.0054, 0.0026, 1.1633};
  for (int i = 0; i < 5; ++i) EXPECT_DOUBLE_EQ(config.camera.distortion.at<double>(i), k[i]);
  EXPECT_DOUBLE_EQ(config.camera.min_depth, 0.3);
  EXPECT_DOUBLE_EQ(config.camera.max_depth, 6.0);
  EXPECT_EQ(config.orb.num_features, 1000);
  EXPECT_EQ(config.orb.num_levels, 8);
  EXPECT_DOUBLE_EQ(config.orb.scale_factor, 1.2);
  EXPECT_EQ(config.tracking.search_radius_px, 15);
  EXPECT_DOUBLE_EQ(config.tracking.chi2_outlier, 5.991);
}

TEST_F(ConfigFileTest, TheTemplateLoadsAndOverridesDefaults) {
  // Guards the error tests below: each differs from a loadable file by one edit.
  const std::string path = write("valid.yaml", kValidYaml);
  SystemConfig config;
  ASSERT_NO_THROW(config = loadConfig(path));
  EXPECT_DOUBLE_EQ(config.camera.fx, 517.3);
  EXPECT_DOUBLE_EQ(config.tracking.max_point_depth, 6.0);
  // Keys left out keep their defaults.
  EXPECT_EQ(config.orb.fast_threshold, OrbOptions().fast_threshold);
  EXPECT_EQ(config.tracking.min_tracked_points, TrackingOptions().min_tracked_points);

  const std::string edited = writeEdited("edited.yaml", "num_features: 1000", "num_features: 500");
  EXPECT_EQ(loadConfig(edited).orb.num_features, 500);
}

TEST_F(ConfigFileTest, OmittedSectionKeepsDefaults) {
  // Sections are optional like their keys: a file without tracking: uses TrackingOptions().
  std::string text = kValidYaml;
  text.erase(text.find("tracking:"));
  SystemConfig config;
  ASSERT_NO_THROW(config = loadConfig(write("no_tracking.yaml", text)))
      << "a config without a tracking section fails";
  EXPECT_EQ(config.tracking.search_radius_px, TrackingOptions().search_radius_px);
  EXPECT_EQ(config.orb.num_features, 1000);
}

TEST_F(ConfigFileTest, OnlyIntrinsicsAndSizeAreRequired) {
  // config/*.yaml: "Every key is optional except camera intrinsics and image size".
  const std::string path = write("minimal.yaml",
                                 "camera:\n  fx: 500\n  fy: 500\n  cx: 320\n  cy: 240\n"
                                 "  width: 640\n  height: 480\n");
  SystemConfig config;
  ASSERT_NO_THROW(config = loadConfig(path)) << "a config with only the required keys fails";
  EXPECT_DOUBLE_EQ(config.camera.fx, 500.0);
  EXPECT_FALSE(config.camera.hasDistortion());
}

TEST_F(ConfigFileTest, MissingFile) {
  expectConfigError((dir_ / "does_not_exist.yaml").string(), {"cannot open"});
}

TEST_F(ConfigFileTest, InvalidYaml) {
  expectConfigError(write("bad.yaml", "camera:\n  fx: [517.3\n  fy: 516.5\n"), {"YAML"});
  expectConfigError(write("list.yaml", "- 1\n- 2\n"), {"top level"});
}

TEST_F(ConfigFileTest, MissingRequiredKeys) {
  expectConfigError(writeEdited("no_fx.yaml", "  fx: 517.3\n", ""), {"camera.fx", "required"});
  expectConfigError(writeEdited("no_height.yaml", "  height: 480\n", ""), {"camera.height"});
  expectConfigError(write("no_camera.yaml", "orb:\n  num_features: 1000\n"), {"camera"});
}

TEST_F(ConfigFileTest, MisspeltKeyAnywhere) {
  // At every nesting level and in every section: silently falling back to a default would hide
  // the user's setting.
  expectConfigError(writeEdited("orb.yaml", "num_features:", "num_feature:"),
                    {"orb.num_feature", "not a known key"});
  expectConfigError(writeEdited("camera.yaml", "  fy:", "  fy: 516.5\n  fz:"), {"camera.fz"});
  expectConfigError(writeEdited("noise.yaml", "    beta:", "    betta:"),
                    {"camera.depth_noise.betta"});
  expectConfigError(writeEdited("tracking.yaml", "nn_ratio:", "nn_ration:"),
                    {"tracking.nn_ration"});
}

TEST_F(ConfigFileTest, MisspeltSectionName) {
  // The section then counts as absent (defaults) and its misspelt name as an unknown key.
  expectConfigError(writeEdited("top.yaml", "tracking:", "trackng:"),
                    {"trackng", "not a known key"});
}

TEST_F(ConfigFileTest, WrongType) {
  expectConfigError(writeEdited("fx_text.yaml", "fx: 517.3", "fx: five hundred"),
                    {"camera.fx", "wrong type"});
  expectConfigError(writeEdited("width_real.yaml", "width: 640", "width: 640.5"),
                    {"camera.width", "wrong type"});
  expectConfigError(writeEdited("levels_list.yaml", "num_levels: 8", "num_levels: [8]"),
                    {"orb.num_levels", "wrong type"});
  expectConfigError(
      writeEdited("distortion_scalar.yaml",
                  "distortion: [0.2624, -0.9531, -0.0054, 0.0026, 1.1633]", "distortion: 0.2624"),
      {"camera.distortion"});
  expectConfigError(writeEdited("section_scalar.yaml",
                                "orb:\n  num_features: 1000\n  "
                                "num_levels: 8\n  scale_factor: 1.2\n",
                                "orb: 7\n"),
                    {"orb"});
}

TEST_F(ConfigFileTest, NegativeOrZeroValues) {
  expectConfigError(writeEdited("fx.yaml", "fx: 517.3", "fx: -517.3"), {"camera.fx", "> 0"});
  expectConfigError(writeEdited("width.yaml", "width: 640", "width: 0"), {"camera.width"});
  expectConfigError(writeEdited("factor.yaml", "depth_factor: 5000.0", "depth_factor: -1"),
                    {"camera.depth_factor"});
  expectConfigError(writeEdited("features.yaml", "num_features: 1000", "num_features: -5"),
                    {"orb.num_features"});
  expectConfigError(writeEdited("radius.yaml", "search_radius_px: 15", "search_radius_px: -15"),
                    {"tracking.search_radius_px"});
  expectConfigError(writeEdited("scale.yaml", "scale_factor: 1.2", "scale_factor: 0.8"),
                    {"orb.scale_factor"});
  expectConfigError(writeEdited("noise.yaml", "gamma: 1.0e-6", "gamma: -1.0"),
                    {"camera.depth_noise"});
}

TEST_F(ConfigFileTest, DepthNoiseQuarticTerm) {
  // delta Z^4: the disparity error of structured light and stereo (sigma_Z grows with Z^2).
  const SystemConfig c = loadConfig(
      writeEdited("delta.yaml", "    gamma: 1.0e-6\n", "    gamma: 0.0\n    delta: 2.5e-5\n"));
  EXPECT_DOUBLE_EQ(c.camera.depth_noise.delta, 2.5e-5);
  // Against the map: sigma_Z = 5e-3 Z^2 beside alpha's 2.5e-3 Z, 4.6 cm at 3 m; within a frame
  // and between frames a moment apart, alpha's alone.
  EXPECT_NEAR(std::sqrt(c.camera.depth_noise.varianceAgainstMap(3.0)),
              std::sqrt(6.25e-6 * 9 + 2.5e-5 * 81), 1e-12);
  EXPECT_NEAR(c.camera.depth_noise.variance(3.0), 6.25e-6 * 9, 1e-15);
  expectConfigError(writeEdited("negative_delta.yaml", "    gamma: 1.0e-6\n",
                                "    gamma: 1.0e-6\n    delta: -1.0e-5\n"),
                    {"camera.depth_noise.delta", "[0, 1]"});
}

TEST_F(ConfigFileTest, MaxDepthNotAboveMinDepth) {
  expectConfigError(writeEdited("equal.yaml", "max_depth: 6.0", "max_depth: 0.3"),
                    {"camera.max_depth", "min_depth"});
  expectConfigError(writeEdited("below.yaml", "max_depth: 6.0", "max_depth: 0.2"),
                    {"camera.max_depth"});
}

// A NaN, an infinity or an absurd number must not pass: fx 1e-300 and a NaN distortion sent
// dense points to infinity (a crash), fy .inf and a NaN noise model ran silently wrong.
TEST_F(ConfigFileTest, NotFiniteOrAbsurdNumbersNameTheKey) {
  expectConfigError(writeEdited("tiny_fx.yaml", "fx: 517.3", "fx: 1e-300"), {"camera.fx"});
  expectConfigError(writeEdited("inf_fy.yaml", "fy: 516.5", "fy: .inf"), {"camera.fy", "finite"});
  expectConfigError(writeEdited("huge_cx.yaml", "cx: 318.6", "cx: 1e9"), {"camera.cx"});
  expectConfigError(writeEdited("nan_distortion.yaml", "[0.2624, -0.9531,", "[.nan, -0.9531,"),
                    {"camera.distortion", "finite"});
  expectConfigError(writeEdited("nan_readout.yaml", "  depth_factor:",
                                "  rolling_shutter_readout: .nan\n  depth_factor:"),
                    {"camera.rolling_shutter_readout", "finite"});
  expectConfigError(writeEdited("nan_alpha.yaml", "alpha: 6.25e-6", "alpha: .nan"),
                    {"camera.depth_noise.alpha", "finite"});
  expectConfigError(writeEdited("nan_factor.yaml", "depth_factor: 5000.0", "depth_factor: .nan"),
                    {"camera.depth_factor"});
  expectConfigError(writeEdited("nan_ratio.yaml", "nn_ratio: 0.9", "nn_ratio: .nan"),
                    {"tracking.nn_ratio", "finite"});
  expectConfigError(writeEdited("inf_depth.yaml", "max_point_depth: 6.0", "max_point_depth: .inf"),
                    {"tracking.max_point_depth", "finite"});
  const std::string base = kValidYaml;
  expectConfigError(write("nan_voxel.yaml", base + "dense:\n  voxel_size: .nan\n"),
                    {"dense.voxel_size", "finite"});
  expectConfigError(write("nan_drift.yaml", base + "loop_correction:\n  max_drift_floor_m: .nan\n"),
                    {"loop_correction.max_drift_floor_m"});
  // Finite but absurd: both crashed ply_slam_tum (a sweep of every key at +-1e9 / 1e+-300).
  expectConfigError(write("stride.yaml", base + "dense:\n  stride: 1000000000\n"),
                    {"dense.stride"});
  expectConfigError(write("resolution.yaml", base + "dense:\n  octree_resolution: 1e-300\n"),
                    {"dense.octree_resolution"});
}

// yaml-cpp keeps both copies of a repeated key and finds the first: the second would be
// ignored without a word.
TEST_F(ConfigFileTest, ARepeatedKeyIsAnErrorNamingIt) {
  expectConfigError(writeEdited("twice.yaml", "  fy: 516.5\n", "  fy: 516.5\n  fx: 600\n"),
                    {"camera.fx", "twice"});
  const std::string base = kValidYaml;
  expectConfigError(write("section_twice.yaml", base + "orb:\n  num_features: 500\n"),
                    {"orb", "twice"});
  EXPECT_THROW(loadConfigFromString(base + "dense:\n  stride: 2\n  stride: 4\n", "text"),
               ConfigError);
}

// yaml-cpp shares an aliased node: an alias inside its own anchor made the duplicate-key walk
// recurse until the stack overflowed (issue #53, exit 139), in every tool that reads a config.
TEST_F(ConfigFileTest, AnAliasInsideItsOwnAnchorIsAnErrorNamingTheFile) {
  expectConfigError(write("cycle.yaml", "a: &x [*x]\n"), {"alias", "cycle"});
  expectConfigError(writeEdited("fx_cycle.yaml", "  fx: 517.3\n", "  fx: &x [*x]\n"),
                    {"alias", "cycle"});
  expectConfigError(write("map_cycle.yaml", std::string(kValidYaml) + "dense: &d {a: *d}\n"),
                    {"cycle"});
}

// The billion laughs: l0 a list of 10 scalars, each lN a list of 10 aliases of l(N-1). 20 kB
// that expand to 10^N nodes; N = 9 took longer than 75 s before (issue #53), N = 8 39 s.
std::string aliasBomb(int levels) {
  std::string text = "l0: &l0 [x, x, x, x, x, x, x, x, x, x]\n";
  for (int n = 1; n <= levels; ++n) {
    const std::string prev = "*l" + std::to_string(n - 1);
    text += "l" + std::to_string(n) + ": &l" + std::to_string(n) + " [" + prev;
    for (int i = 1; i < 10; ++i) text += ", " + prev;
    text += "]\n";
  }
  return text;
}

TEST_F(ConfigFileTest, NestedAliasesAreRefusedAtOnceNamingTheFile) {
  const auto start = std::chrono::steady_clock::now();
  expectConfigError(write("bomb.yaml", std::string(kValidYaml) + aliasBomb(9)),
                    {"aliases expanded"});
  expectConfigError(write("bomb5.yaml", std::string(kValidYaml) + aliasBomb(5)),
                    {"aliases expanded"});
  EXPECT_THROW(loadConfigFromString(std::string(kValidYaml) + aliasBomb(9), "text"), ConfigError);
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(5));
  // A few aliases as a user writes them stay allowed, and a bomb small enough is only an
  // unknown key.
  expectConfigError(write("bomb3.yaml", std::string(kValidYaml) + aliasBomb(3)),
                    {"l0", "not a known key"});
  std::string shared = kValidYaml;
  shared.replace(shared.find("  fx: 517.3"), 11, "  fx: &f 517.3");
  shared.replace(shared.find("  fy: 516.5"), 11, "  fy: *f");
  EXPECT_EQ(loadConfig(write("shared.yaml", shared)).camera.fy, 517.3);
}

TEST_F(ConfigFileTest, ADocumentNestedTooDeepIsAnErrorNamingTheFile) {
  const std::string deep =
      std::string(kValidYaml) + "dense: " + std::string(100, '[') + std::string(100, ']') + "\n";
  expectConfigError(write("deep.yaml", deep), {"deeper than"});
}

TEST_F(ConfigFileTest, ADirectoryIsAnErrorNamingIt) {
  expectConfigError(dir_.string(), {"directory"});
}

// Opening a named pipe waits for a writer: the tools hung for ever (issue #53).
TEST_F(ConfigFileTest, ANamedPipeOrADeviceIsAnErrorNamingIt) {
  const std::string fifo = (dir_ / "f.yaml").string();
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  expectConfigError(fifo, {"named pipe"});
  expectConfigError("/dev/zero", {"device"});
}

TEST_F(ConfigFileTest, DistortionNeedsFourOrFiveCoefficients) {
  expectConfigError(writeEdited("three.yaml", "[0.2624, -0.9531, -0.0054, 0.0026, 1.1633]",
                                "[0.2624, -0.9531, -0.0054]"),
                    {"camera.distortion", "4 or 5"});
  expectConfigError(writeEdited("six.yaml", "[0.2624, -0.9531, -0.0054, 0.0026, 1.1633]",
                                "[0.1, 0.1, 0.1, 0.1, 0.1, 0.1]"),
                    {"camera.distortion"});
  // Four coefficients are accepted (k3 = 0).
  const std::string four = writeEdited("four.yaml", "[0.2624, -0.9531, -0.0054, 0.0026, 1.1633]",
                                       "[0.1, -0.2, 0.003, 0.004]");
  SystemConfig config;
  ASSERT_NO_THROW(config = loadConfig(four));
  EXPECT_EQ(config.camera.distortion.total(), 4u);
  EXPECT_TRUE(config.camera.hasDistortion());
}

// The dense section: values are read, and bad ones are named.
TEST_F(ConfigFileTest, DenseSection) {
  const std::string base = kValidYaml;
  const SystemConfig config =
      loadConfig(write("dense.yaml", base + "dense:\n  stride: 4\n  colour_mode: rgb\n  "
                                            "octree_occupancy: 0.7\n  ray_margin: 0.05\n"));
  EXPECT_EQ(config.dense.stride, 4);
  EXPECT_EQ(config.dense.colour_mode, OctreeColourMode::kRgb);
  EXPECT_DOUBLE_EQ(config.dense.octree_occupancy, 0.7);
  EXPECT_DOUBLE_EQ(config.dense.ray_margin, 0.05);
  EXPECT_DOUBLE_EQ(config.dense.octree_resolution, DenseOptions().octree_resolution);
  expectConfigError(write("mode.yaml", base + "dense:\n  colour_mode: hue\n"),
                    {"dense.colour_mode", "class or rgb"});
  expectConfigError(write("occ.yaml", base + "dense:\n  octree_occupancy: 0.3\n"),
                    {"dense.octree_occupancy"});
  expectConfigError(write("margin.yaml", base + "dense:\n  ray_margin: -0.1\n"),
                    {"dense.ray_margin"});
  expectConfigError(write("range.yaml", base + "dense:\n  min_depth: 2\n  max_depth: 1\n"),
                    {"dense.max_depth"});
  expectConfigError(write("key.yaml", base + "dense:\n  voxel: 0.02\n"),
                    {"dense.voxel", "not a known key"});
}

// The grid section: values are read, the up vector normalised, bad ones named.
TEST_F(ConfigFileTest, GridSection) {
  const std::string base = kValidYaml;
  const SystemConfig config = loadConfig(
      write("grid.yaml", base + "grid:\n  robot_height: 0.4\n  floor: given\n  up: [0, -2, 0]\n"
                                "  floor_height: -0.8\n"));
  EXPECT_DOUBLE_EQ(config.grid.robot_height, 0.4);
  EXPECT_EQ(config.grid.floor, "given");
  EXPECT_DOUBLE_EQ(config.grid.up.y(), -1.0);
  EXPECT_DOUBLE_EQ(config.grid.floor_height, -0.8);
  EXPECT_DOUBLE_EQ(config.grid.floor_clearance, OccupancyGridOptions().floor_clearance);
  expectConfigError(write("floor.yaml", base + "grid:\n  floor: lowest\n"),
                    {"grid.floor", "auto or given"});
  expectConfigError(
      write("band.yaml", base + "grid:\n  floor_clearance: 0.3\n  robot_height: 0.2\n"),
      {"grid.robot_height", "floor_clearance"});
  expectConfigError(write("up.yaml", base + "grid:\n  up: [0, 1]\n"), {"grid.up", "3 numbers"});
  expectConfigError(write("zero.yaml", base + "grid:\n  up: [0, 0, 0]\n"), {"grid.up"});
  expectConfigError(write("res.yaml", base + "grid:\n  resolution: 0\n"), {"grid.resolution"});
  expectConfigError(write("key.yaml", base + "grid:\n  height: 0.3\n"),
                    {"grid.height", "not a known key"});
}

// Every shipped file has the grid of a TurtleBot3 on a floor found from the data.
TEST(ShippedConfig, GridForATurtleBot3) {
  for (const char* file :
       {"tum_fr1.yaml", "tum_fr2.yaml", "tum_fr3.yaml", "d435i.yaml", "bonn.yaml"}) {
    const OccupancyGridOptions grid = loadConfig(kConfigDir + file).grid;
    EXPECT_TRUE(grid.enabled) << file;
    EXPECT_EQ(grid.floor, "auto") << file;
    EXPECT_DOUBLE_EQ(grid.resolution, 0.05) << file;
    EXPECT_DOUBLE_EQ(grid.floor_clearance, 0.1) << file;
    EXPECT_DOUBLE_EQ(grid.robot_height, 0.25) << file;
  }
}

TEST_F(ConfigFileTest, LinesSurfaceBand) {
  const std::string base = kValidYaml;
  EXPECT_EQ(
      loadConfig(write("band.yaml", base + "lines:\n  surface_band_px: 8\n")).lines.surface_band_px,
      8);
  EXPECT_EQ(
      loadConfig(write("off.yaml", base + "lines:\n  surface_band_px: 0\n")).lines.surface_band_px,
      0);
  EXPECT_EQ(loadConfig(write("none.yaml", base)).lines.surface_band_px,
            LineOptions().surface_band_px);
  expectConfigError(write("one.yaml", base + "lines:\n  surface_band_px: 1\n"),
                    {"lines.surface_band_px", "0 (off) or within [2, 20]"});
  expectConfigError(write("wide.yaml", base + "lines:\n  surface_band_px: 21\n"),
                    {"lines.surface_band_px"});
}

// The loop section: read through the loop module's reader, errors name the file;
// the depth noise comes from the camera; "" vocabulary paths mean the trained defaults.
TEST_F(ConfigFileTest, LoopSection) {
  const std::string base = kValidYaml;
  const SystemConfig config =
      loadConfig(write("loop.yaml", base + "loop:\n  enabled: true\n  orb_vocabulary: voc/o.voc\n"
                                           "  min_normalised_score: 0.45\n  match_ratio: 0.7\n"));
  EXPECT_TRUE(config.loop.enabled);
  EXPECT_EQ(config.loop.orb_vocabulary, "voc/o.voc");
  EXPECT_EQ(config.loop.lbd_vocabulary, "");
  EXPECT_DOUBLE_EQ(config.loop.min_normalised_score, 0.45);
  EXPECT_DOUBLE_EQ(config.loop.match_ratio, 0.7);
  EXPECT_DOUBLE_EQ(config.loop.depth_noise.alpha, 6.25e-6);  // the template camera's
  EXPECT_FALSE(loadConfig(write("none.yaml", base)).loop.enabled);
  expectConfigError(write("key.yaml", base + "loop:\n  alpha: 0.3\n"),
                    {"loop.alpha", "not a known key"});
  expectConfigError(write("type.yaml", base + "loop:\n  enabled: maybe\n"),
                    {"loop.enabled", "wrong type"});
  expectConfigError(write("range.yaml", base + "loop:\n  match_ratio: 1.5\n"),
                    {"loop.match_ratio"});
  expectConfigError(write("map.yaml", base + "loop: 3\n"), {"loop"});
}

TEST(ShippedConfig, LoopClosureOnWithTheDefaultVocabularies) {
  const LoopCorrectionOptions defaults;
  for (const char* file :
       {"tum_fr1.yaml", "tum_fr2.yaml", "tum_fr3.yaml", "d435i.yaml", "bonn.yaml"}) {
    const SystemConfig config = loadConfig(kConfigDir + file);
    EXPECT_TRUE(config.loop.enabled) << file;
    // The files spell out the defaults (one place to read them, one to change them).
    const LoopCorrectionOptions& c = config.loop_correction;
    EXPECT_EQ(c.strong_covisibility, defaults.strong_covisibility) << file;
    EXPECT_EQ(c.max_drift_fraction, defaults.max_drift_fraction) << file;
    EXPECT_EQ(c.max_drift_floor_m, defaults.max_drift_floor_m) << file;
    EXPECT_EQ(c.min_keyframes_between, defaults.min_keyframes_between) << file;
    EXPECT_EQ(c.pose_graph.rotation_sigma_rad, defaults.pose_graph.rotation_sigma_rad) << file;
    EXPECT_EQ(c.global_ba_iterations, defaults.global_ba_iterations) << file;
    EXPECT_EQ(config.loop.orb_vocabulary, "") << file;
    EXPECT_EQ(config.loop.lbd_vocabulary, "") << file;
    EXPECT_EQ(config.loop.consistency, 3) << file;
    const CullingOptions culling_defaults;
    EXPECT_EQ(config.culling.keyframes.redundancy, culling_defaults.keyframes.redundancy) << file;
    EXPECT_EQ(config.culling.keyframes.min_observers, culling_defaults.keyframes.min_observers)
        << file;
    EXPECT_EQ(config.culling.points.min_found_ratio, culling_defaults.points.min_found_ratio)
        << file;
    EXPECT_EQ(config.culling.points.probation_keyframes,
              culling_defaults.points.probation_keyframes)
        << file;
  }
}

TEST(CullingSection, ValuesReachTheOptionsAndBadOnesNameTheKey) {
  const std::string base =
      "camera: {fx: 500, fy: 500, cx: 320, cy: 240, width: 640, height: 480}\n";
  const SystemConfig config = loadConfigFromString(
      base + "culling: {keyframe_redundancy: 1.0, keyframe_level_slack: 0, point_min_visible: 5}\n",
      "test");
  EXPECT_EQ(config.culling.keyframes.redundancy, 1.0);
  EXPECT_EQ(config.culling.keyframes.level_slack, 0);
  EXPECT_EQ(config.culling.points.min_visible, 5);
  EXPECT_EQ(config.culling.points.min_found_ratio, 0.25);  // not given: the default
  try {
    loadConfigFromString(base + "culling: {keyframe_redundancy: 1.5}\n", "test");
    FAIL() << "a redundancy above 1 was accepted";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("culling.keyframe_redundancy"), std::string::npos)
        << e.what();
  }
  EXPECT_THROW(loadConfigFromString(base + "culling: {redundancy: 0.9}\n", "test"), ConfigError);
  EXPECT_THROW(loadConfigFromString(base + "culling: {point_min_found_ratio: -0.1}\n", "test"),
               ConfigError);
}

TEST(LoopCorrectionSection, OutOfRangeAndUnknownKeysNameTheKey) {
  const std::string base =
      "camera: {fx: 500, fy: 500, cx: 320, cy: 240, width: 640, height: 480}\n";
  try {
    loadConfigFromString(base + "loop_correction: {max_drift_fraction: -0.1}\n", "test");
    FAIL() << "a negative drift fraction was accepted";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("loop_correction.max_drift_fraction"), std::string::npos)
        << e.what();
  }
  EXPECT_THROW(loadConfigFromString(base + "loop_correction: {pose_graph_iteration: 3}\n", "test"),
               ConfigError);
  EXPECT_EQ(loadConfigFromString(base + "loop_correction: {global_ba_iterations: 0}\n", "test")
                .loop_correction.global_ba_iterations,
            0);
}

// String modes are parsed once, when the config is loaded: enums in the options, the same error
// messages for a word that is not one.
TEST_F(ConfigFileTest, ModesAreParsedIntoEnums) {
  const std::string base = kValidYaml;
  const SystemConfig defaults = loadConfig(write("defaults.yaml", base));
  EXPECT_EQ(defaults.dynamic.mode, DynamicMode::kFull);
  EXPECT_EQ(defaults.lines.balance, LineBalance::kPaper);
  EXPECT_EQ(defaults.lines.detector, LineDetectorChoice::kAuto);
  EXPECT_EQ(defaults.dense.colour_mode, OctreeColourMode::kClass);
  const SystemConfig config =
      loadConfig(write("modes.yaml", base + "dynamic:\n  mode: semantic\nlines:\n  balance: one\n  "
                                            "detector: edlines\n"));
  EXPECT_EQ(config.dynamic.mode, DynamicMode::kSemantic);
  EXPECT_STREQ(toString(config.dynamic.mode), "semantic");
  EXPECT_EQ(config.lines.balance, LineBalance::kOne);
  EXPECT_STREQ(toString(config.lines.balance), "one");
  EXPECT_EQ(config.lines.detector, LineDetectorChoice::kEdlines);
  expectConfigError(write("dyn.yaml", base + "dynamic:\n  mode: fast\n"),
                    {"dynamic.mode", "must be off, geometric, semantic or full"});
  expectConfigError(write("bal.yaml", base + "lines:\n  balance: two\n"),
                    {"lines.balance", "must be paper or one"});
  expectConfigError(write("det.yaml", base + "lines:\n  detector: hough\n"),
                    {"lines.detector", "must be auto, lsd or edlines"});
  EXPECT_EQ(parseDynamicMode("off"), DynamicMode::kOff);
  EXPECT_THROW(parseDynamicMode("Full"), std::invalid_argument);
  EXPECT_EQ(modeWithoutSegmenter(DynamicMode::kFull), DynamicMode::kGeometric);
  EXPECT_EQ(modeWithoutSegmenter(DynamicMode::kSemantic), DynamicMode::kSemantic);
}

// Ceres settings: the defaults are the values the code had written in, each solver section is
// read over its module's defaults, and bad values are named.
TEST_F(ConfigFileTest, SolverSections) {
  const std::string base = kValidYaml;
  const SystemConfig defaults = loadConfig(write("defaults.yaml", base));
  const SolverOptions& pose = defaults.tracking.pose_solver;
  EXPECT_EQ(pose.linear_solver, LinearSolver::kDenseQr);
  EXPECT_EQ(pose.max_iterations, 10);
  EXPECT_DOUBLE_EQ(pose.function_tolerance, 1e-3);
  const SolverOptions& bundle = defaults.mapping.bundle_solver;
  EXPECT_EQ(bundle.linear_solver, LinearSolver::kSparseSchur);
  EXPECT_EQ(bundle.max_iterations, 10);
  EXPECT_DOUBLE_EQ(bundle.function_tolerance, 1e-6);
  EXPECT_EQ(defaults.loop_correction.pose_graph.linear_solver, LinearSolver::kSparseNormalCholesky);
  EXPECT_EQ(loadConfig(write("graph.yaml",
                             base + "loop_correction:\n  pose_graph_linear_solver: dense_qr\n"))
                .loop_correction.pose_graph.linear_solver,
            LinearSolver::kDenseQr);
  expectConfigError(
      write("graph_bad.yaml", base + "loop_correction:\n  pose_graph_linear_solver: lu\n"),
      {"loop_correction.pose_graph_linear_solver", "must be dense_qr"});

  const SystemConfig config = loadConfig(
      write("solvers.yaml", base + "mapping:\n  bundle_solver:\n    linear_solver: dense_schur\n"
                                   "    max_iterations: 4\n"));
  EXPECT_EQ(config.mapping.bundle_solver.linear_solver, LinearSolver::kDenseSchur);
  EXPECT_EQ(config.mapping.bundle_solver.max_iterations, 4);
  EXPECT_DOUBLE_EQ(config.mapping.bundle_solver.parameter_tolerance, 1e-8);  // kept
  const SystemConfig tracking = loadConfig(
      writeEdited("pose.yaml", "  max_point_depth: 6.0\n",
                  "  max_point_depth: 6.0\n  pose_solver:\n    function_tolerance: 1.0e-4\n"));
  EXPECT_DOUBLE_EQ(tracking.tracking.pose_solver.function_tolerance, 1e-4);
  EXPECT_EQ(tracking.tracking.pose_solver.max_iterations, 10);  // kept

  expectConfigError(write("ls.yaml", base + "mapping:\n  bundle_solver:\n    linear_solver: cg\n"),
                    {"mapping.bundle_solver.linear_solver", "must be dense_qr"});
  expectConfigError(writeEdited("it.yaml", "  max_point_depth: 6.0\n",
                                "  max_point_depth: 6.0\n  pose_solver:\n    max_iterations: 0\n"),
                    {"tracking.pose_solver.max_iterations"});
  expectConfigError(write("key.yaml", base + "mapping:\n  bundle_solver:\n    iterations: 3\n"),
                    {"mapping.bundle_solver.iterations", "not a known key"});
  expectConfigError(write("map.yaml", base + "mapping:\n  local_map_keyframes: 3\n"),
                    {"mapping.local_map_keyframes", "not a known key"});
}

// The mapping side takes tracking's local-map window and outlier bound (the keys stay in
// tracking:), and the rest of what it needs from the other sections.
TEST_F(ConfigFileTest, MapperOptionsFollowTheirSections) {
  const SystemConfig config =
      loadConfig(writeEdited("mapper.yaml", "  nn_ratio: 0.9\n",
                             "  nn_ratio: 0.9\n  local_map_keyframes: 7\n  chi2_outlier: 4.5\n"));
  EXPECT_EQ(config.mapping.window_keyframes, 7);
  EXPECT_DOUBLE_EQ(config.mapping.chi2_outlier, 4.5);
  const MapperOptions mapper = mapperOptions(config);
  EXPECT_EQ(mapper.local.window_keyframes, 7);
  EXPECT_DOUBLE_EQ(mapper.local.chi2_outlier, 4.5);
  EXPECT_EQ(mapper.orb.num_levels, config.orb.num_levels);
  EXPECT_EQ(mapper.mask_dilation_px, config.dynamic.mask_dilation_px);
  EXPECT_EQ(mapper.loop.enabled, config.loop.enabled);
  EXPECT_EQ(mapper.loop_correction.global_ba_iterations,
            config.loop_correction.global_ba_iterations);
}

// The tuning constants that were written into the tracker and the landmark fuser: options with
// those values, read from their sections.
TEST_F(ConfigFileTest, FormerConstantsAreOptions) {
  const std::string base = kValidYaml;
  const SystemConfig defaults = loadConfig(write("defaults.yaml", base));
  EXPECT_EQ(defaults.tracking.pnp_min_matches, 15);
  EXPECT_DOUBLE_EQ(defaults.tracking.max_velocity_gap_s, 0.2);
  EXPECT_DOUBLE_EQ(defaults.mapping.fuse_radius_px, 3.0);
  EXPECT_EQ(defaults.mapping.fuse_max_descriptor_distance, 50);
  const SystemConfig config = loadConfig(write(
      "fuse.yaml", base + "mapping:\n  fuse_radius_px: 2.5\n  fuse_max_descriptor_distance: 40\n"));
  EXPECT_DOUBLE_EQ(config.mapping.fuse_radius_px, 2.5);
  EXPECT_EQ(config.mapping.fuse_max_descriptor_distance, 40);
  EXPECT_EQ(loadConfig(writeEdited("pnp.yaml", "  nn_ratio: 0.9\n",
                                   "  nn_ratio: 0.9\n  pnp_min_matches: 20\n"))
                .tracking.pnp_min_matches,
            20);
  expectConfigError(write("dist.yaml", base + "mapping:\n  fuse_max_descriptor_distance: 300\n"),
                    {"mapping.fuse_max_descriptor_distance"});
  expectConfigError(
      writeEdited("pnp_bad.yaml", "  nn_ratio: 0.9\n", "  nn_ratio: 0.9\n  pnp_min_matches: 3\n"),
      {"tracking.pnp_min_matches", "must be >= 4"});
  expectConfigError(
      writeEdited("gap.yaml", "  nn_ratio: 0.9\n", "  nn_ratio: 0.9\n  max_velocity_gap_s: 0\n"),
      {"tracking.max_velocity_gap_s", "must be > 0"});
}

// Found by fuzz/fuzz_config: a list or map as a key ("? " form) threw yaml-cpp's
// TypedBadConversion out of loadConfig instead of a ConfigError naming the section.
TEST(ConfigText, AKeyThatIsNotANameIsAConfigError) {
  const std::string base =
      "camera: {fx: 500, fy: 500, cx: 320, cy: 240, width: 640, height: 480}\n";
  try {
    loadConfigFromString(base + "dynamic:\n  ? {mode: full}\n  : 1\n", "test");
    FAIL() << "a map as a key was accepted";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("dynamic."), std::string::npos) << e.what();
  }
  EXPECT_THROW(loadConfigFromString(base + "? [a, b]\n: 1\n", "test"), ConfigError);
}

// Issue #53: yaml-cpp's Load reads the first document and drops the rest without a word, so a
// camera given after "---" was ignored.
TEST_F(ConfigFileTest, ASecondYamlDocumentIsRefused) {
  const std::string path = write("two.yaml", std::string(kValidYaml) + "---\ncamera: {fx: 1}\n");
  expectConfigError(path, {"2 YAML documents"});
  try {
    loadConfig(path);
  } catch (const ConfigError& e) {
    EXPECT_EQ(std::string(e.what()).find("cannot read"), std::string::npos) << e.what();
  }
  EXPECT_THROW(loadConfigFromString(std::string(kValidYaml) + "---\n---\n", "text"), ConfigError);
  EXPECT_NO_THROW(loadConfigFromString(std::string("---\n") + kValidYaml, "text"));
}

// Issue #53: a valid-looking 4-coefficient list with p2 = 1.16 (fr1's k2 left out) cannot be
// undistorted at the border: dense points went kilometres out and the run took minutes.
TEST_F(ConfigFileTest, ADistortionThatCannotBeUndistortedIsRefused) {
  const std::string fr1 = "distortion: [0.2624, -0.9531, -0.0054, 0.0026, 1.1633]";
  expectConfigError(writeEdited("p2.yaml", fr1, "distortion: [0.2624, -0.0054, 0.0026, 1.1633]"),
                    {"camera.distortion", "cannot be undistorted at the image border"});
  expectConfigError(writeEdited("k1.yaml", fr1, "distortion: [-1.0, 0, 0, 0]"),
                    {"camera.distortion", "cannot be undistorted"});
  EXPECT_NO_THROW(loadConfig(writeEdited("k1_small.yaml", fr1, "distortion: [-0.1, 0, 0, 0]")));
}

// Issue #53: orb.edge_threshold 100000 left no pixel to extract from and tracked nothing.
TEST_F(ConfigFileTest, AnOrbBorderWiderThanAnImageIsRefused) {
  expectConfigError(writeEdited("edge.yaml", "  scale_factor: 1.2\n",
                                "  scale_factor: 1.2\n  edge_threshold: 100000\n"),
                    {"orb.edge_threshold", "must lie in [1, 100]"});
  const std::string fine = writeEdited("edge31.yaml", "  scale_factor: 1.2\n",
                                       "  scale_factor: 1.2\n  edge_threshold: 31\n");
  EXPECT_EQ(loadConfig(fine).orb.edge_threshold, 31);
}

// What a tracker apart and its mapping_node must agree on (ApartMappingSide refuses the rest).
TEST(MappingSettings, OnlyTheKeysTheMappingSideReadsCount) {
  const std::string base =
      "camera: {fx: 500, fy: 500, cx: 320, cy: 240, width: 640, height: 480}\n";
  auto config = [&](const std::string& more) { return loadConfigFromString(base + more, "test"); };
  const SystemConfig plain = config("orb: {num_levels: 8}\nculling: {keyframe_redundancy: 0.9}\n");
  EXPECT_TRUE(mappingSettingsThatDiffer(plain, plain).empty());
  // The same values written otherwise, in another order, beside keys the mapping side does not
  // read (another camera is the jobs' camera's business).
  const SystemConfig same = loadConfigFromString(
      "camera: {fx: 600, fy: 600, cx: 320, cy: 240, width: 640, height: 480}\n"
      "culling: {keyframe_redundancy: 0.90}\ndense: {stride: 4}\n"
      "tracking: {search_radius_px: 30}\norb: {num_levels: 8}\n",
      "test");
  EXPECT_TRUE(mappingSettingsThatDiffer(plain, same).empty());
  // A section given in one and not the other differs whole; within one, key by key.
  const SystemConfig other = config(
      "orb: {num_levels: 4}\ntracking: {max_point_depth: 3, search_radius_px: 30}\n"
      "loop: {enabled: false}\n");
  EXPECT_EQ(
      mappingSettingsThatDiffer(plain, other),
      (std::vector<std::string>{"orb.num_levels", "loop", "culling", "tracking.max_point_depth"}));
  EXPECT_EQ(mappingSettingsThatDiffer(other, plain), mappingSettingsThatDiffer(plain, other));
}

TEST(MappingSettings, UseCameraReachesThePlaceCheckToo) {
  SystemConfig config = loadConfigFromString(
      "camera: {fx: 500, fy: 500, cx: 320, cy: 240, width: 640, height: 480}\n", "test");
  PinholeCamera camera = config.camera;
  camera.fx = 615;
  camera.depth_noise.alpha = 3e-4;
  useCamera(config, camera);
  EXPECT_EQ(config.camera.fx, 615);
  EXPECT_EQ(config.loop.depth_noise.alpha, 3e-4);
}

}  // namespace
}  // namespace ply_slam
