#include "ply_slam/synth/synthetic_sequence_writer.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <locale>
#include <mutex>
#include <opencv2/core/utility.hpp>
#include <opencv2/imgcodecs.hpp>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "ply_slam/common/stopwatch.h"
#include "ply_slam/io/tum_trajectory_file.h"

namespace ply_slam {
namespace {

namespace fs = std::filesystem;

// PNG level 1: a third of the default's encoding time for a few percent more bytes.
const std::vector<int> kPngParams = {cv::IMWRITE_PNG_COMPRESSION, 1};

void writeText(const fs::path& path, const std::string& text) {
  std::ofstream out(path);
  out << text;
  out.close();
  if (!out) throw std::runtime_error(path.string() + ": cannot write");
}

void writePng(const fs::path& path, const cv::Mat& image) {
  bool ok = false;
  try {
    ok = cv::imwrite(path.string(), image, kPngParams);
  } catch (const cv::Exception&) {
    ok = false;
  }
  if (!ok) throw std::runtime_error(path.string() + ": cannot write");
}

// Metres to 16-bit units; 0 where there is no depth or it does not fit.
cv::Mat depthPng(const cv::Mat& depth, double factor) {
  cv::Mat out(depth.size(), CV_16UC1);
  for (int y = 0; y < depth.rows; ++y) {
    const float* in = depth.ptr<float>(y);
    uint16_t* o = out.ptr<uint16_t>(y);
    for (int x = 0; x < depth.cols; ++x) {
      const double units = std::round(in[x] * factor);
      o[x] = (in[x] > 0.0f && units <= 65535.0) ? static_cast<uint16_t>(units) : 0;
    }
  }
  return out;
}

std::string stampText(double stamp) {
  std::ostringstream s;
  s.imbue(std::locale::classic());
  s << std::fixed << std::setprecision(6) << stamp;
  return s.str();
}

}  // namespace

std::string cameraYaml(const PinholeCamera& c, const std::string& comment) {
  std::ostringstream y;
  y.imbue(std::locale::classic());
  y << std::setprecision(10);
  y << "# " << comment << "\n"
    << "# Written by ply_slam_synth; orb and tracking keep the library defaults.\n"
    << "camera:\n"
    << "  fx: " << c.fx << "\n  fy: " << c.fy << "\n  cx: " << c.cx << "\n  cy: " << c.cy
    << "\n  width: " << c.width << "\n  height: " << c.height << "\n"
    << "  distortion: [0.0, 0.0, 0.0, 0.0, 0.0]\n"
    << "  depth_factor: " << c.depth_factor << "\n"
    << "  min_depth: " << c.min_depth << "\n  max_depth: " << c.max_depth << "\n"
    << "  depth_noise:  # sigma_Z^2 = alpha Z^2 + beta Z + gamma (+ delta Z^4 against the map; "
       "m^2)\n"
    << "    alpha: " << c.depth_noise.alpha << "\n    beta: " << c.depth_noise.beta
    << "\n    gamma: " << c.depth_noise.gamma << "\n    delta: " << c.depth_noise.delta << "\n";
  return y.str();
}

namespace {

void createFolders(const fs::path& root) {
  std::error_code ec;
  for (const char* sub : {"rgb", "depth", "masks"}) {
    fs::create_directories(root / sub, ec);
    if (ec || !fs::is_directory(root / sub))
      throw std::runtime_error(root.string() + ": cannot create the output folder (" +
                               ec.message() + ")");
  }
}

// camera.yaml, instances.txt and lines.txt: what the scene is, independent of the frames.
void writeSceneFiles(const SyntheticSequence& seq, const fs::path& root) {
  const SynthOptions& o = seq.options();
  const Scene& scene = seq.scene();
  std::ostringstream comment;
  comment << "synthetic " << scene.name() << " scene, " << o.walkers << " walkers, " << o.frames
          << " frames, seed " << o.seed << (o.loop ? ", loop" : "")
          << (o.noise ? ", sensor noise" : ", exact depth (quantised to 1/5000 m)");
  writeText(root / "camera.yaml", cameraYaml(seq.sensorCamera(), comment.str()));

  std::ostringstream instances;
  instances << "# instance id, COCO class name with '_' for spaces (ids as in masks/)\n";
  for (const Walker& w : scene.walkers()) instances << w.instance() << " person\n";
  for (auto [id, class_name] : scene.objectClasses()) {
    std::replace(class_name.begin(), class_name.end(), ' ',
                 '_');  // one field (readInstanceClasses)
    instances << id << " " << class_name << "\n";
  }
  writeText(root / "instances.txt", instances.str());

  std::ostringstream lines;
  lines.imbue(std::locale::classic());
  lines << "# 3D line segments of the static scene, world frame (m): x1 y1 z1 x2 y2 z2\n"
        << std::setprecision(9);
  for (const Segment3& l : scene.lines())
    lines << l.a.x() << " " << l.a.y() << " " << l.a.z() << " " << l.b.x() << " " << l.b.y() << " "
          << l.b.z() << "\n";
  writeText(root / "lines.txt", lines.str());
}

// The three encodings of a frame are independent: one per thread.
void writeFrameImages(const std::pair<fs::path, cv::Mat> (&images)[3]) {
  std::string failure;
  std::mutex failure_mutex;
  cv::parallel_for_(cv::Range(0, 3), [&](const cv::Range& range) {
    for (int k = range.start; k < range.end; ++k) {
      try {
        writePng(images[k].first, images[k].second);
      } catch (const std::exception& e) {
        std::lock_guard<std::mutex> lock(failure_mutex);
        failure = e.what();
      }
    }
  });
  if (!failure.empty()) throw std::runtime_error(failure);
}

// The frame lists TUM's tools read and the ground truth, filled frame by frame.
struct FrameLists {
  std::ostringstream rgb, depth, masks, associations;
  Trajectory ground_truth;

  FrameLists() {
    rgb << "# color images\n# timestamp filename\n";
    depth << "# depth maps (metres x 5000)\n# timestamp filename\n";
    masks << "# instance masks (instances.txt)\n# timestamp filename\n";
  }

  void write(const fs::path& root) const {
    writeText(root / "rgb.txt", rgb.str());
    writeText(root / "depth.txt", depth.str());
    writeText(root / "masks.txt", masks.str());
    writeText(root / "associations.txt", associations.str());
    try {
      writeTumTrajectory((root / "groundtruth.txt").string(), ground_truth);
    } catch (const std::exception& e) {
      throw std::runtime_error((root / "groundtruth.txt").string() + ": cannot write (" + e.what() +
                               ")");
    }
  }
};

// Renders frame i, writes its images and lists them.
void writeFrame(const SyntheticSequence& seq, int i, const fs::path& root, FrameLists& lists,
                SynthWriteStats& stats) {
  Stopwatch render_clock;
  const RenderedFrame f = seq.render(i);
  stats.render_ms += render_clock.elapsedMs();

  Stopwatch write_clock;
  const std::string stamp = stampText(seq.stamp(i));
  const std::string rgb = "rgb/" + stamp + ".png", depth = "depth/" + stamp + ".png",
                    mask = "masks/" + stamp + ".png";
  writeFrameImages({{root / rgb, f.rgb},
                    {root / depth, depthPng(f.depth, seq.camera().depth_factor)},
                    {root / mask, f.instance}});
  stats.write_ms += write_clock.elapsedMs();

  lists.rgb << stamp << " " << rgb << "\n";
  lists.depth << stamp << " " << depth << "\n";
  lists.masks << stamp << " " << mask << "\n";
  lists.associations << stamp << " " << rgb << " " << stamp << " " << depth << "\n";
  lists.ground_truth.push_back({seq.stamp(i), seq.pose(i)});
  ++stats.frames;
}

}  // namespace

SynthWriteStats writeSyntheticSequence(const SyntheticSequence& seq, const std::string& dir,
                                       const std::function<void(int)>& progress) {
  const fs::path root(dir);
  createFolders(root);
  writeSceneFiles(seq, root);
  FrameLists lists;
  SynthWriteStats stats;
  for (int i = 0; i < seq.size(); ++i) {
    writeFrame(seq, i, root, lists, stats);
    if (progress) progress(i);
  }
  lists.write(root);
  return stats;
}

}  // namespace ply_slam
