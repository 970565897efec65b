// Synthetic sequences: the written folder must be exactly consistent with its ground truth
// (depth + poses + intrinsics move a pixel onto the same texture point in another frame, the
// lines lie on image edges, walkers are masked where they are seen) and readable by the
// rest of the library.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "ply_slam/io/tum_sequence.h"
#include "ply_slam/semantic/mask_folder_segmenter.h"
#include "ply_slam/synth/synthetic_sequence.h"
#include "ply_slam/synth/synthetic_sequence_writer.h"
#include "ply_slam/system/system_config.h"

namespace ply_slam {
namespace {

namespace fs = std::filesystem;

constexpr int kFrames = 12;
constexpr int kWalkers = 2;
constexpr double kPi = 3.14159265358979323846;

bool texturesInstalled() { return fs::exists(std::string(kDefaultTextureDir) + "/graf1.png"); }

#define REQUIRE_TEXTURES()                                                                  \
  do {                                                                                      \
    if (!texturesInstalled()) GTEST_SKIP() << "opencv-doc missing: " << kDefaultTextureDir; \
  } while (0)

// One office sequence with two walkers, written once for all tests of the suite.
class WrittenOffice : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    if (!texturesInstalled()) return;
    dir_ = new fs::path(fs::temp_directory_path() /
                        ("ply_slam_test_synth_" + std::to_string(::getpid())));
    fs::remove_all(*dir_);
    SynthOptions o;
    o.frames = kFrames;
    o.walkers = kWalkers;
    o.seed = 7;
    seq_ = new SyntheticSequence(o);
    writeSyntheticSequence(*seq_, dir_->string());
  }
  static void TearDownTestSuite() {
    if (dir_) fs::remove_all(*dir_);
    delete dir_;
    delete seq_;
    dir_ = nullptr;
    seq_ = nullptr;
  }
  void SetUp() override { REQUIRE_TEXTURES(); }
  static std::string path(const std::string& relative) { return (*dir_ / relative).string(); }

  static fs::path* dir_;
  static SyntheticSequence* seq_;
};
fs::path* WrittenOffice::dir_ = nullptr;
SyntheticSequence* WrittenOffice::seq_ = nullptr;

std::vector<Segment3> readLines(const std::string& file) {
  std::ifstream in(file);
  std::vector<Segment3> lines;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream s(line);
    Segment3 l;
    s >> l.a.x() >> l.a.y() >> l.a.z() >> l.b.x() >> l.b.y() >> l.b.z();
    EXPECT_FALSE(s.fail()) << file << ": " << line;
    lines.push_back(l);
  }
  return lines;
}

// Bilinear interpolation of a 32FC1 image at a position inside it.
double bilinear(const cv::Mat& image, const Eigen::Vector2d& p) {
  const int x = static_cast<int>(std::floor(p.x())), y = static_cast<int>(std::floor(p.y()));
  const double fx = p.x() - x, fy = p.y() - y;
  const float* r0 = image.ptr<float>(y);
  const float* r1 = image.ptr<float>(y + 1);
  return (1 - fy) * ((1 - fx) * r0[x] + fx * r0[x + 1]) + fy * ((1 - fx) * r1[x] + fx * r1[x + 1]);
}

// (d) The folder parses as a TUM sequence, camera.yaml loads, the images are the rendering.
TEST_F(WrittenOffice, FolderLoadsWithTheLibraryReaders) {
  const TumSequence tum(dir_->string());
  ASSERT_EQ(tum.size(), static_cast<size_t>(kFrames));
  EXPECT_TRUE(tum.usedAssociationsFile());
  EXPECT_EQ(tum.unassociatedRgbFrames(), 0u);
  ASSERT_TRUE(tum.hasGroundTruth());
  ASSERT_EQ(tum.groundTruth().size(), static_cast<size_t>(kFrames));
  const SystemConfig config = loadConfig(path("camera.yaml"));
  EXPECT_EQ(config.camera.fx, 525.0);
  EXPECT_EQ(config.camera.fy, 525.0);
  EXPECT_EQ(config.camera.cx, 319.5);
  EXPECT_EQ(config.camera.cy, 239.5);
  EXPECT_EQ(config.camera.width, 640);
  EXPECT_EQ(config.camera.height, 480);
  EXPECT_EQ(config.camera.depth_factor, 5000.0);
  EXPECT_FALSE(config.camera.hasDistortion());

  for (int i : {0, kFrames - 1}) {
    const RgbdImages images = tum.load(i, config.camera.depth_factor);
    EXPECT_NEAR(images.stamp, seq_->stamp(i), 1e-6);
    EXPECT_NEAR(tum.groundTruth()[i].stamp, images.stamp, 1e-9);
    const RenderedFrame f = seq_->render(i);
    cv::Mat diff;
    cv::absdiff(images.rgb, f.rgb, diff);
    EXPECT_EQ(cv::countNonZero(diff.reshape(1)), 0);
    double max_error = 0.0;
    for (int y = 0; y < f.depth.rows; ++y)
      for (int x = 0; x < f.depth.cols; ++x)
        max_error = std::max(max_error, std::abs(images.depth.at<float>(y, x) -
                                                 static_cast<double>(f.depth.at<float>(y, x))));
    EXPECT_LE(max_error, 0.5 / 5000.0 + 1e-6);  // half a depth unit
    const Eigen::Isometry3d& gt = tum.groundTruth()[i].T_wc;
    EXPECT_LT((gt.matrix() - seq_->pose(i).matrix()).cwiseAbs().maxCoeff(), 1e-6);
    const cv::Mat mask =
        cv::imread(path("masks/") + fs::path(tum.record(i).rgb_path).filename().string(),
                   cv::IMREAD_UNCHANGED);
    ASSERT_EQ(mask.type(), CV_8UC1);
    EXPECT_EQ(cv::countNonZero(mask != f.instance), 0);
  }
  EXPECT_GT(readLines(path("lines.txt")).size(), 100u);
}

// (a) Back-project with the written depth, move with the written poses, project with the
// written intrinsics: the pixel lands on the same texture point (the renderer's surface
// coordinates, located to sub-pixel precision in the other frame).
TEST_F(WrittenOffice, PixelsTransferToTheSameTexturePoint) {
  const TumSequence tum(dir_->string());
  const PinholeCamera cam = loadConfig(path("camera.yaml")).camera;
  int compared = 0;
  double sum = 0.0, worst = 0.0;
  for (auto [i, j] : {std::pair{0, 4}, {4, 8}, {3, 11}, {11, 1}}) {
    const cv::Mat depth_i = tum.load(i, cam.depth_factor).depth;
    const Eigen::Isometry3d T_ji = tum.groundTruth()[j].T_wc.inverse() * tum.groundTruth()[i].T_wc;
    const RenderedFrame fi = seq_->renderExact(i), fj = seq_->renderExact(j);
    for (int y = 2; y < cam.height - 2; y += 4) {
      for (int x = 2; x < cam.width - 2; x += 4) {
        const float z = depth_i.at<float>(y, x);
        const int id = fi.instance.at<uint8_t>(y, x);
        if (z <= 0.0f || (id != 0 && id < Scene::kFirstObjectInstance)) continue;  // walkers move
        const Eigen::Vector3d p_j = T_ji * cam.backProject({x, y}, z);
        if (p_j.z() < 0.1) continue;
        const Eigen::Vector2d uv = cam.project(p_j);
        if (!cam.inImage(uv, 2.0)) continue;
        const int x0 = static_cast<int>(std::floor(uv.x())),
                  y0 = static_cast<int>(std::floor(uv.y()));
        const int surface = fi.surface.at<int>(y, x);
        bool same = true;  // all four neighbours show the same quad: not occluded, no border
        for (int dy = 0; dy <= 1; ++dy)
          for (int dx = 0; dx <= 1; ++dx)
            same = same && fj.surface.at<int>(y0 + dy, x0 + dx) == surface;
        if (!same) continue;
        // Surface coordinates are (locally) affine in the pixel position on a plane: solve
        // for where frame j sees the texture point of pixel (x, y) of frame i.
        const cv::Vec2f c00 = fj.surface_coords.at<cv::Vec2f>(y0, x0);
        const cv::Vec2f c10 = fj.surface_coords.at<cv::Vec2f>(y0, x0 + 1);
        const cv::Vec2f c01 = fj.surface_coords.at<cv::Vec2f>(y0 + 1, x0);
        const cv::Vec2f target = fi.surface_coords.at<cv::Vec2f>(y, x);
        Eigen::Matrix2d J;
        J << c10[0] - c00[0], c01[0] - c00[0], c10[1] - c00[1], c01[1] - c00[1];
        const Eigen::Vector2d d =
            J.inverse() * Eigen::Vector2d(target[0] - c00[0], target[1] - c00[1]);
        const double error = (Eigen::Vector2d(x0 + d.x(), y0 + d.y()) - uv).norm();
        sum += error;
        worst = std::max(worst, error);
        ++compared;
      }
    }
  }
  std::cout << "[ transfer ] " << compared << " pixels, mean " << sum / compared << " px, max "
            << worst << " px\n";
  EXPECT_GT(compared, 5000);
  EXPECT_LT(worst, 0.5);
  EXPECT_LT(sum / compared, 0.05);
}

// Samples of lines on image edges, accumulated over frames.
struct EdgeCheck {
  int line_views = 0;  // (line, frame) pairs with a visible sample
  int visible = 0;     // samples where the line is in view and not occluded
  int peaked = 0;      // ... with a gradient peak across the line within 1 px
  int strongest = 0;   // ... where the strongest gradient within +-3 px is within 1 px
  double share() const { return static_cast<double>(peaked) / std::max(visible, 1); }
  std::string summary() const {
    std::ostringstream s;
    s << line_views << " line views, " << visible
      << " visible samples, gradient peak within 1 px: " << 100.0 * share()
      << " % (the strongest within +-3 px is within 1 px: "
      << 100.0 * strongest / std::max(visible, 1) << " %)";
    return s.str();
  }
};

// Samples each segment every 2 px of its projection into a frame (rgb, depth as written, pose
// T_wc, the quads rendered) and looks across it for a peak of the intensity gradient.
void checkLinesOnEdges(const std::vector<Segment3>& lines, const cv::Mat& rgb, const cv::Mat& depth,
                       const Eigen::Isometry3d& T_wc, const std::vector<Quad>& quads,
                       const RayCaster& caster, const PinholeCamera& cam, EdgeCheck* check) {
  constexpr double kProfile = 3.0;      // px searched on each side
  constexpr double kMinGradient = 3.0;  // grey levels per pixel
  cv::Mat grey, gx, gy;
  cv::cvtColor(rgb, grey, cv::COLOR_BGR2GRAY);
  grey.convertTo(grey, CV_32F);
  cv::Sobel(grey, gx, CV_32F, 1, 0, 3, 1.0 / 8.0);
  cv::Sobel(grey, gy, CV_32F, 0, 1, 3, 1.0 / 8.0);
  const Eigen::Isometry3d T_cw = T_wc.inverse();
  auto depthAt = [&](const Eigen::Vector2d& p) {
    return depth.at<float>(static_cast<int>(std::lround(p.y())),
                           static_cast<int>(std::lround(p.x())));
  };
  for (const Segment3& line : lines) {
    Eigen::Vector3d a = T_cw * line.a, b = T_cw * line.b;
    if (a.z() < 0.2 && b.z() < 0.2) continue;
    // Clip to the part in front of the camera.
    if (a.z() < 0.2) a = a + (b - a) * ((0.2 - a.z()) / (b.z() - a.z()));
    if (b.z() < 0.2) b = b + (a - b) * ((0.2 - b.z()) / (a.z() - b.z()));
    const Eigen::Vector2d ua = cam.project(a), ub = cam.project(b);
    const double length = (ub - ua).norm();
    if (length < 20.0) continue;
    const Eigen::Vector2d dir = (ub - ua) / length, normal(-dir.y(), dir.x());
    bool seen = false;
    const int n = static_cast<int>(std::min(length, 4000.0) / 2.0);
    for (int k = 0; k <= n; ++k) {
      // Uniform in the image; the matching 3D point by inverse-depth interpolation.
      const double s = static_cast<double>(k) / n;
      const double w = s / b.z() / ((1 - s) / a.z() + s / b.z());
      const Eigen::Vector3d p = a + w * (b - a);
      const Eigen::Vector2d uv = cam.project(p);
      // Away from the ends (corners, junctions) and from the image border.
      if (s * length < 5.0 || (1 - s) * length < 5.0 || !cam.inImage(uv, 6.0)) continue;
      // Visible: the ray through the point meets nothing nearer (an exact ray cast into the
      // scene: the hidden back edge of a 5 cm desk leg is only 5 cm behind its front), and no
      // walker covers the profile.
      const RayHit hit = caster.cast(quads, T_wc, uv);
      if (hit.surface < 0 || hit.depth < p.z() * (1.0 - 1e-6)) continue;
      bool covered = false;
      for (double o = -kProfile; o <= kProfile; o += 0.5) {
        const double d = depthAt(uv + o * normal);
        covered = covered || d <= 0.0 || d < p.z() - (0.1 + 0.02 * p.z());
      }
      if (covered) continue;
      ++check->visible;
      seen = true;
      // Directional derivative across the segment, every 0.25 px.
      std::vector<double> g;
      for (double o = -kProfile; o <= kProfile + 1e-9; o += 0.25) {
        const Eigen::Vector2d q = uv + o * normal;
        g.push_back(std::abs(bilinear(gx, q) * normal.x() + bilinear(gy, q) * normal.y()));
      }
      const int centre = static_cast<int>(g.size()) / 2, reach = 4;  // 4 steps = 1 px
      // A peak: a local maximum within 1 px with real contrast; another edge a few pixels
      // away (the other side of a door jamb or a desk leg) may be stronger.
      bool peak = false;
      for (int k = centre - reach; k <= centre + reach; ++k)
        peak = peak || (g[k] >= kMinGradient && g[k] >= g[k - 1] && g[k] >= g[k + 1]);
      check->peaked += peak;
      const int strongest = static_cast<int>(std::max_element(g.begin(), g.end()) - g.begin());
      check->strongest += std::abs(strongest - centre) <= reach;
    }
    check->line_views += seen;
  }
}

// (b) Every lines.txt segment lies on an image edge where visible: across the projected
// segment, the intensity gradient peaks within 1 px of it.
TEST_F(WrittenOffice, LinesLieOnImageEdges) {
  const TumSequence tum(dir_->string());
  const PinholeCamera cam = loadConfig(path("camera.yaml")).camera;
  const std::vector<Segment3> lines = readLines(path("lines.txt"));
  EdgeCheck check;
  for (int i : {0, 5, 11}) {
    const RgbdImages images = tum.load(i, cam.depth_factor);
    checkLinesOnEdges(lines, images.rgb, images.depth, tum.groundTruth()[i].T_wc,
                      seq_->scene().quadsAt(seq_->time(i)), seq_->caster(), cam, &check);
  }
  std::cout << "[ lines ] office: " << check.summary() << "\n";
  EXPECT_GT(check.line_views, 60);
  EXPECT_GT(check.visible, 5000);
  EXPECT_GE(check.share(), 0.9);
}

// The same in the other scenes, rendered in memory.
TEST(SyntheticSequence, LinesLieOnImageEdgesInEveryScene) {
  REQUIRE_TEXTURES();
  for (SceneKind kind : {SceneKind::kLowTexture, SceneKind::kCorridor, SceneKind::kRing}) {
    SynthOptions o;
    o.scene = kind;
    o.walkers = kind == SceneKind::kRing ? 0 : 1;  // the ring has no room for people
    o.frames = 90;
    const SyntheticSequence seq(o);
    EdgeCheck check;
    for (int i : {0, 45, 89}) {
      const RenderedFrame f = seq.render(i);
      cv::Mat depth;  // as written: 1/5000 m units
      f.depth.convertTo(depth, CV_16UC1, 5000.0);
      depth.convertTo(depth, CV_32F, 1.0 / 5000.0);
      checkLinesOnEdges(seq.scene().lines(), f.rgb, depth, seq.pose(i),
                        seq.scene().quadsAt(seq.time(i)), seq.caster(), seq.camera(), &check);
    }
    std::cout << "[ lines ] " << sceneKindName(kind) << ": " << check.summary() << "\n";
    EXPECT_GT(check.visible, 2000) << sceneKindName(kind);
    EXPECT_GE(check.share(), 0.9) << sceneKindName(kind);
  }
}

// (c) Walkers: their pixels belong to a person, are nearer than the static scene behind them,
// and show a walker's surface. Labelled objects (the desk, the monitor): their
// pixels show the static scene unchanged, on a quad of that object. Unmasked pixels show the
// static scene unchanged.
TEST_F(WrittenOffice, WalkersAreMaskedAndOccludeTheScene) {
  const std::map<int, std::string> classes = readInstanceClasses(path("instances.txt"));
  int walkers = 0;
  for (const auto& [id, name] : classes) {
    if (id >= Scene::kFirstObjectInstance) {
      EXPECT_TRUE(name == "tv" || name == "dining table") << id << " " << name;
      continue;
    }
    ++walkers;
    EXPECT_EQ(name, "person") << id;
  }
  EXPECT_EQ(walkers, kWalkers);
  EXPECT_EQ(classes.size() - walkers, seq_->scene().objectClasses().size());
  EXPECT_EQ(seq_->scene().objectClasses().size(), 2u);  // the desk and the monitor
  const std::vector<Quad>& statics = seq_->scene().staticQuads();
  const int static_quads = static_cast<int>(statics.size());
  long masked = 0, objects = 0, wrong = 0;
  for (int i = 0; i < kFrames; i += 2) {
    const RenderedFrame f = seq_->renderExact(i, true), s = seq_->renderExact(i, false);
    for (int y = 0; y < f.depth.rows; ++y) {
      for (int x = 0; x < f.depth.cols; ++x) {
        const int id = f.instance.at<uint8_t>(y, x);
        const float z = f.depth.at<float>(y, x), z_static = s.depth.at<float>(y, x);
        const int surface = f.surface.at<int>(y, x);
        if (id == 0 || id >= Scene::kFirstObjectInstance) {
          wrong += z != z_static || surface >= static_quads;
          if (id != 0) {
            ++objects;
            wrong += !classes.count(id) || statics[surface].instance != id;
          }
          continue;
        }
        ++masked;
        wrong += !classes.count(id) || !(z < z_static) || surface < static_quads;
      }
    }
  }
  std::cout << "[ objects ] " << objects << " labelled pixels\n";
  EXPECT_GT(objects, 1000);
  std::cout << "[ walkers ] " << masked << " masked pixels in " << (kFrames + 1) / 2 << " frames\n";
  EXPECT_GT(masked, 10000);  // they are in view
  EXPECT_EQ(wrong, 0);

  // They walk at walking speed and stay in the room.
  for (const Walker& w : seq_->scene().walkers()) {
    const double dt = 0.1;
    for (double t = 0.0; t < 20.0; t += dt) {
      const Eigen::Vector3d p = w.pose(t).translation();
      EXPECT_NEAR((w.pose(t + dt).translation() - p).norm() / dt, 1.2, 0.05);
      for (int axis = 0; axis < 2; ++axis) {
        EXPECT_GT(p[axis], seq_->scene().boundsMin()[axis] + 0.3);
        EXPECT_LT(p[axis], seq_->scene().boundsMax()[axis] - 0.3);
      }
    }
  }
}

TEST(SyntheticSequence, NoWalkersOnlyObjectsMasked) {
  REQUIRE_TEXTURES();
  const fs::path dir =
      fs::temp_directory_path() / ("ply_slam_test_synth_empty_" + std::to_string(::getpid()));
  SynthOptions o;
  o.frames = 3;
  o.walkers = 0;
  const SyntheticSequence seq(o);
  writeSyntheticSequence(seq, dir.string());
  int files = 0;
  for (const auto& entry : fs::directory_iterator(dir / "masks")) {
    const cv::Mat mask = cv::imread(entry.path().string(), cv::IMREAD_UNCHANGED);
    ASSERT_EQ(mask.type(), CV_8UC1);
    EXPECT_EQ(cv::countNonZero((mask != 0) & (mask < Scene::kFirstObjectInstance)), 0);
    EXPECT_GT(cv::countNonZero(mask), 0);  // the desk is in view
    ++files;
  }
  EXPECT_EQ(files, 3);
  const std::map<int, std::string> classes = readInstanceClasses((dir / "instances.txt").string());
  EXPECT_EQ(classes.size(), seq.scene().objectClasses().size());
  EXPECT_EQ(classes, seq.scene().objectClasses());  // "dining table" read back with its space
  fs::remove_all(dir);
}

// (e) --loop: the camera returns to its first pose; without it, it does not.
TEST(SyntheticSequence, LoopEndsWhereItStarted) {
  REQUIRE_TEXTURES();
  for (SceneKind kind : {SceneKind::kOffice, SceneKind::kCorridor}) {
    SynthOptions o;
    o.scene = kind;
    o.frames = 90;
    o.loop = true;
    const SyntheticSequence loop(o);
    const Eigen::Matrix4d first = loop.pose(0).matrix(), last = loop.pose(o.frames - 1).matrix();
    EXPECT_LT((first - last).cwiseAbs().maxCoeff(), 1e-9) << sceneKindName(kind);
    o.loop = false;
    const SyntheticSequence open(o);
    EXPECT_GT((open.pose(0).translation() - open.pose(o.frames - 1).translation()).norm(), 0.05)
        << sceneKindName(kind);
  }
}

// Hand-held motion: about 0.3 m/s and 30 deg/s, and never facing a wall closer than 0.8 m.
TEST(SyntheticSequence, CameraPathIsHandHeldAndLooksIntoTheRoom) {
  REQUIRE_TEXTURES();
  for (SceneKind kind : {SceneKind::kOffice, SceneKind::kLowTexture, SceneKind::kCorridor}) {
    for (bool loop : {false, true}) {
      SynthOptions o;
      o.scene = kind;
      o.loop = loop;
      o.seed = 3;
      const SyntheticSequence seq(o);
      const std::string what = sceneKindName(kind) + (loop ? " loop" : "");
      // About: the extents that keep the camera looking into the room may cap the speeds.
      EXPECT_NEAR(seq.path().meanLinearSpeed(), 0.28, 0.04) << what;
      EXPECT_NEAR(seq.path().meanAngularSpeed() * 180.0 / kPi, 27.0, 6.0) << what;
      const PinholeCamera& cam = seq.camera();
      double nearest = 1e9;
      for (int i = 0; i < seq.size(); i += 3) {
        const RayHit hit =
            seq.caster().cast(seq.scene().staticQuads(), seq.pose(i), {cam.cx, cam.cy});
        ASSERT_GE(hit.surface, 0) << what;
        nearest = std::min(nearest, hit.depth);
      }
      EXPECT_GT(nearest, 0.8) << what;
    }
  }
}

// The circuit alone: four smooth left turns that bring the walk back to its start.
TEST(Circuit, ClosesAndTurnsSmoothly) {
  const Eigen::Vector2d start(1.0, -2.0), size(5.0, 3.0);
  const Circuit c(start, 0.3, size, 1.2);
  const Circuit::Place end = c.at(c.length());
  EXPECT_LT((end.position - start).norm(), 1e-9);
  EXPECT_NEAR(end.heading, 0.3 + 2.0 * kPi, 1e-12);
  double max_rate = 0.0, max_step = 0.0;
  const double ds = 0.001;
  for (double s = 0.0; s + ds <= c.length(); s += ds) {
    const Circuit::Place a = c.at(s), b = c.at(s + ds);
    max_step = std::max(max_step, (b.position - a.position).norm() / ds);
    max_rate = std::max(max_rate, (b.heading - a.heading) / ds);
  }
  EXPECT_NEAR(max_step, 1.0, 1e-6);  // arc length is distance walked
  EXPECT_NEAR(max_rate, c.maxCurvature(), 0.01);
  EXPECT_THROW(Circuit(start, 0.0, {1.0, 3.0}, 1.2), std::invalid_argument);
}

// The ring's camera goes once round at a hand-held pace, turns corners at a human rate, stays
// in the corridor and is back at its first pose, having seen nothing of the start for a
// long time in between.
class RingPath : public ::testing::Test {
 protected:
  void SetUp() override {
    REQUIRE_TEXTURES();
    SynthOptions o;
    o.scene = SceneKind::kRing;
    o.frames = defaultFrames(SceneKind::kRing);
    o.loop = true;
    seq_ = std::make_unique<SyntheticSequence>(o);
  }
  std::unique_ptr<SyntheticSequence> seq_;
};

TEST_F(RingPath, EndsWhereItStarted) {
  const Eigen::Isometry3d first = seq_->pose(0), last = seq_->pose(seq_->size() - 1);
  EXPECT_LT((first.translation() - last.translation()).norm(), 1e-3);
  EXPECT_LT(Eigen::AngleAxisd(first.linear().transpose() * last.linear()).angle(),
            0.1 * kPi / 180.0);
}

TEST_F(RingPath, MovesAtHandHeldSpeeds) {
  EXPECT_NEAR(seq_->path().meanLinearSpeed(), 0.4, 0.1);
  EXPECT_NEAR(seq_->path().meanAngularSpeed() * 180.0 / kPi, 30.0, 6.0);
  // Without the sway: the walk's own turn rate at the corners.
  CameraPathSpec walk = buildScene(SceneKind::kRing, 0, kDefaultTextureDir).camera;
  walk.position_extent.setZero();
  walk.angle_extent.setZero();
  const CameraPath path(walk, seq_->size(), seq_->options().fps, true, 1);
  double max_rate = 0.0;
  for (int i = 1; i < path.frames(); ++i) {
    const Eigen::Matrix3d R =
        path.poseAtFrame(i - 1).linear().transpose() * path.poseAtFrame(i).linear();
    max_rate = std::max(max_rate, Eigen::AngleAxisd(R).angle() * path.fps());
  }
  EXPECT_GT(max_rate * 180.0 / kPi, 25.0);  // it does turn
  EXPECT_LT(max_rate * 180.0 / kPi, 40.0);
}

TEST_F(RingPath, StaysInTheCorridor) {
  // The ring's walls (scene_library.cpp): outer 8 x 6 m, the block from (2, 2) to (6, 4).
  constexpr double kClearance = 0.5;  // m: beyond the sensor's 0.4 m minimum range
  for (int i = 0; i < seq_->size(); ++i) {
    const Eigen::Vector3d p = seq_->pose(i).translation();
    const double to_block =
        std::max({2.0 - p.x(), p.x() - 6.0, 2.0 - p.y(), p.y() - 4.0});  // outside: > 0
    const double to_outer = std::min({p.x(), 8.0 - p.x(), p.y(), 6.0 - p.y()});
    ASSERT_GT(std::min(to_block, to_outer), kClearance) << "frame " << i;
  }
}

// Loop detection only compares keyframes at least 10 s apart: the surfaces in the first view
// are out of sight from 10 s after the start until 10 s before the end.
TEST_F(RingPath, LeavesTheStartOutOfSightInBetween) {
  const PinholeCamera& cam = seq_->camera();
  const std::vector<Quad>& quads = seq_->scene().staticQuads();
  std::vector<Eigen::Vector3d> seen;  // world points of the first view
  for (int y = 20; y < cam.height; y += 40)
    for (int x = 20; x < cam.width; x += 40) {
      const Eigen::Vector2d uv(x, y);
      const RayHit hit = seq_->caster().cast(quads, seq_->pose(0), uv);
      if (hit.surface >= 0) seen.push_back(hit.world);
    }
  ASSERT_GT(seen.size(), 150u);
  const int gap = static_cast<int>(10.0 * seq_->options().fps);
  for (int i = gap; i < seq_->size() - gap; i += 10) {
    const Eigen::Isometry3d T_cw = seq_->pose(i).inverse();
    int visible = 0;
    for (const Eigen::Vector3d& w : seen) {
      const Eigen::Vector3d c = T_cw * w;
      if (c.z() < 0.1 || !cam.inImage(cam.project(c), 0.0)) continue;
      const RayHit hit = seq_->caster().cast(quads, seq_->pose(i), cam.project(c));
      visible += hit.surface >= 0 && hit.depth > c.z() - 0.01;
    }
    ASSERT_EQ(visible, 0) << "frame " << i;
  }
}

TEST(SyntheticSequence, RingHasNoWalkers) {
  REQUIRE_TEXTURES();
  EXPECT_THROW(buildScene(SceneKind::kRing, 1, kDefaultTextureDir), std::invalid_argument);
}

TEST(SyntheticSequence, MissingTexturesNameTheFile) {
  SynthOptions o;
  o.texture_dir = "/nonexistent/textures";
  try {
    const SyntheticSequence seq(o);
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/textures/"), std::string::npos) << e.what();
  }
}

TEST(SyntheticSequence, UnwritableFolderNamesIt) {
  REQUIRE_TEXTURES();
  SynthOptions o;
  o.frames = 2;
  const SyntheticSequence seq(o);
  try {
    writeSyntheticSequence(seq, "/proc/ply_slam_synth_out");
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("/proc/ply_slam_synth_out"), std::string::npos);
  }
}

}  // namespace
}  // namespace ply_slam
