// Renders a synthetic RGB-D sequence with exact ground truth into a TUM-layout folder:
//   ply_slam_synth --out DIR [--scene office|lowtexture|corridor|ring] [--walkers N] [--frames N]
//                  [--loop] [--noise] [--seed S] [--textures DIR]
//   ply_slam_synth --benchmark [--scene ...] [--walkers N] [--frames N] [--noise]
// The benchmark renders (and PNG-encodes in memory) without writing and prints frames/s.
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <iterator>
#include <opencv2/core/utility.hpp>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <vector>

#include "ply_slam/common/angles.h"
#include "ply_slam/common/command_line.h"
#include "ply_slam/common/stopwatch.h"
#include "ply_slam/synth/synthetic_sequence.h"
#include "ply_slam/synth/synthetic_sequence_writer.h"

using namespace ply_slam;

namespace {

constexpr int kBenchmarkFrames = 120;

struct Options {
  SynthOptions synth;
  std::string out;
  bool benchmark = false;
  bool frames_given = false;
};

const char* const kUsage =
    "usage: ply_slam_synth --out DIR [--scene office|lowtexture|corridor|ring]\n"
    "                      [--walkers N] [--frames N] [--loop] [--noise] [--seed S] [--textures "
    "DIR]\n"
    "       ply_slam_synth --benchmark [--scene S] [--walkers N] [--frames N] [--noise]\n";

void setFlag(Options& o, const std::string& flag) {
  (flag == "--loop" ? o.synth.loop : flag == "--noise" ? o.synth.noise : o.benchmark) = true;
}

void setOption(Options& o, const std::string& arg, const std::string& value) {
  if (arg == "--out") {
    o.out = value;
  } else if (arg == "--scene") {
    if (!parseSceneKind(value, &o.synth.scene))
      throw UsageError("unknown scene '" + value + "' (office, lowtexture, corridor or ring)");
  } else if (arg == "--walkers") {
    o.synth.walkers =
        static_cast<int>(wholeNumberArgument(arg, value, 0, Scene::kFirstObjectInstance - 1));
  } else if (arg == "--frames") {
    o.synth.frames = static_cast<int>(wholeNumberArgument(arg, value, 2, 1000000));
    o.frames_given = true;
  } else if (arg == "--seed") {
    o.synth.seed = static_cast<uint64_t>(wholeNumberArgument(arg, value, 0, 2147483647L));
  } else if (arg == "--textures") {
    o.synth.texture_dir = value;
  }
}

Options parse(int argc, char** argv) {
  Options o;
  CommandLine line;
  line.usage_text = kUsage;
  line.flags = {"--loop", "--noise", "--benchmark"};
  line.options = {"--out", "--scene", "--walkers", "--frames", "--seed", "--textures"};
  line.on_flag = [&](const std::string& flag) { setFlag(o, flag); };
  line.on_option = [&](const std::string& arg, const std::string& value) {
    setOption(o, arg, value);
  };
  line.parse(argc, argv);
  if (!o.benchmark && o.out.empty()) throw UsageError("--out DIR is required");
  if (!o.frames_given) o.synth.frames = defaultFrames(o.synth.scene);
  if (o.benchmark && !o.frames_given) o.synth.frames = kBenchmarkFrames;
  return o;
}

int benchmark(const SyntheticSequence& seq) {
  double render_ms = 0.0, encode_ms = 0.0;
  const std::vector<int> png = {cv::IMWRITE_PNG_COMPRESSION, 1};
  for (int i = 0; i < seq.size(); ++i) {
    Stopwatch clock;
    const RenderedFrame f = seq.render(i);
    render_ms += clock.elapsedMs();
    clock.restart();
    cv::Mat depth;
    f.depth.convertTo(depth, CV_16UC1, seq.camera().depth_factor);
    // As the writer does: the three images encoded in parallel.
    const cv::Mat images[] = {f.rgb, depth, f.instance};
    cv::parallel_for_(cv::Range(0, 3), [&](const cv::Range& r) {
      std::vector<uchar> buffer;
      for (int k = r.start; k < r.end; ++k) cv::imencode(".png", images[k], buffer, png);
    });
    encode_ms += clock.elapsedMs();
  }
  const int n = seq.size();
  std::cout << std::fixed << std::setprecision(1) << "benchmark: " << n << " frames "
            << seq.camera().width << "x" << seq.camera().height << ", scene " << seq.scene().name()
            << ", " << seq.options().walkers << " walkers" << (seq.options().noise ? ", noise" : "")
            << ", " << cv::getNumThreads() << " threads\n"
            << "  render:       " << render_ms / n << " ms/frame = " << 1000.0 * n / render_ms
            << " frames/s\n"
            << "  PNG encoding: " << encode_ms / n << " ms/frame\n"
            << "  both:         " << 1000.0 * n / (render_ms + encode_ms) << " frames/s\n";
  return 0;
}

int run(const Options& o) {
  Stopwatch setup_clock;
  const SyntheticSequence seq(o.synth);
  const double setup_ms = setup_clock.elapsedMs();
  if (o.benchmark) return benchmark(seq);

  std::error_code ec;
  std::filesystem::create_directories(o.out, ec);
  if (ec || !std::filesystem::is_directory(o.out)) {
    std::cerr << "ply_slam_synth: cannot create the output folder " << o.out << ": "
              << (ec ? ec.message() : "not a directory") << "\n";
    return 1;
  }
  std::cout << "ply_slam_synth: " << seq.scene().name() << ", " << o.synth.walkers << " walkers, "
            << seq.size() << " frames -> " << o.out << std::endl;
  const SynthWriteStats s = writeSyntheticSequence(seq, o.out, [&](int i) {
    if ((i + 1) % 50 == 0 || i + 1 == seq.size())
      std::cout << "  frame " << i + 1 << "/" << seq.size() << std::endl;
  });
  std::cout << std::fixed << std::setprecision(1) << "scene setup " << setup_ms << " ms; "
            << "render " << s.render_ms / s.frames << " ms/frame ("
            << 1000.0 * s.frames / s.render_ms << " frames/s), PNG writing "
            << s.write_ms / s.frames << " ms/frame; camera path " << std::setprecision(2)
            << seq.path().meanLinearSpeed() << " m/s, " << degrees(seq.path().meanAngularSpeed())
            << " deg/s\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return runTool("ply_slam_synth", kUsage, [&] {
    const Options o = parse(argc, argv);
    try {
      return run(o);
    } catch (const std::invalid_argument& e) {  // options the scene cannot be made with
      throw UsageError(e.what());
    }
  });
}
