// Trains a place-recognition vocabulary (module loop) on the ORB or LBD descriptors that the
// SLAM system's own extractors produce:
//   ply_slam_vocabulary --images DIR|LIST|VIDEO --kind orb|lbd --out FILE [--k 10]
//                       [--levels 5] [--max-features N] [--seed S] [--video-step N]
//                       [--config FILE]
// or measures a pair of vocabularies: load time, and query time against a database of
// keyframes made of noisy copies of the images' descriptors:
//   ply_slam_vocabulary --benchmark --orb-vocabulary FILE --lbd-vocabulary FILE
//                       --images DIR|LIST|VIDEO [--keyframes 2000] [--video-step N]
//
// Exit codes: 0 ok, 1 unreadable data or failed training, 2 usage error.
#include <algorithm>
#include <cstdlib>
#include <iomanip>
#include <iostream>
#include <optional>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "ply_slam/common/command_line.h"
#include "ply_slam/common/statistics.h"
#include "ply_slam/common/stopwatch.h"
#include "ply_slam/features/line_extractor.h"
#include "ply_slam/features/orb_extractor.h"
#include "ply_slam/loop/binary_vocabulary.h"
#include "ply_slam/loop/bow_database.h"
#include "ply_slam/loop/training_images.h"
#include "ply_slam/system/system_config.h"

using namespace ply_slam;

namespace {

constexpr const char* kUsage =
    "usage: ply_slam_vocabulary --images DIR|LIST|VIDEO --kind orb|lbd --out FILE [--k 10]\n"
    "                           [--levels 5] [--max-features N] [--seed S] [--video-step 10]\n"
    "                           [--config FILE]\n"
    "       ply_slam_vocabulary --benchmark --orb-vocabulary FILE --lbd-vocabulary FILE\n"
    "                           --images DIR|LIST|VIDEO [--keyframes 2000] [--video-step 10]\n"
    "  --max-features: ORB keypoints or LBD lines per image (default: the config's, 1000 / 150)\n"
    "  --config: the SLAM config whose orb: and lines: parameters extract the descriptors\n";

struct Options {
  std::string images, out, config, orb_vocabulary, lbd_vocabulary;
  std::optional<DescriptorKind> kind;
  VocabularyParams vocabulary;
  long max_features = 0;  // 0: the config's
  int video_step = 10;
  bool benchmark = false;
  long keyframes = 2000;
};

void setOption(Options& o, const std::string& arg, const std::string& value) {
  if (arg == "--images") {
    o.images = value;
  } else if (arg == "--kind") {
    o.kind = parseDescriptorKind(value);
    if (!o.kind) throw UsageError("--kind needs orb or lbd, got '" + value + "'");
  } else if (arg == "--out") {
    o.out = value;
  } else if (arg == "--config") {
    o.config = value;
  } else if (arg == "--k") {
    o.vocabulary.branching = static_cast<int>(wholeNumberArgument(arg, value, 2, 64));
  } else if (arg == "--levels") {
    o.vocabulary.levels = static_cast<int>(wholeNumberArgument(arg, value, 1, 10));
  } else if (arg == "--max-features") {
    o.max_features = wholeNumberArgument(arg, value, 1, 100000);
  } else if (arg == "--seed") {
    o.vocabulary.seed = static_cast<uint64_t>(wholeNumberArgument(arg, value, 0, 1L << 62));
  } else if (arg == "--video-step") {
    o.video_step = static_cast<int>(wholeNumberArgument(arg, value, 1, 100000));
  } else if (arg == "--orb-vocabulary") {
    o.orb_vocabulary = value;
  } else if (arg == "--lbd-vocabulary") {
    o.lbd_vocabulary = value;
  } else if (arg == "--keyframes") {
    o.keyframes = wholeNumberArgument(arg, value, 1, 1000000);
  } else {
    throw UsageError("unknown option " + arg);
  }
}

Options parse(int argc, char** argv) {
  Options o;
  CommandLine line;
  line.usage_text = kUsage;
  line.flags = {"--benchmark"};
  line.options = {
      "--images",         "--kind",         "--out",  "--config",     "--k",
      "--levels",         "--max-features", "--seed", "--video-step", "--orb-vocabulary",
      "--lbd-vocabulary", "--keyframes"};
  line.on_flag = [&](const std::string&) { o.benchmark = true; };
  line.on_option = [&](const std::string& arg, const std::string& value) {
    setOption(o, arg, value);
  };
  line.parse(argc, argv);
  if (o.images.empty()) throw UsageError("--images is required");
  if (o.benchmark && (o.orb_vocabulary.empty() || o.lbd_vocabulary.empty()))
    throw UsageError("--benchmark needs --orb-vocabulary and --lbd-vocabulary");
  if (!o.benchmark && (!o.kind || o.out.empty())) throw UsageError("--kind and --out are required");
  if (o.kind) o.vocabulary.kind = *o.kind;
  return o;
}

// The descriptors the SLAM system computes for one grey image: ORB points or LBD lines.
class Describer {
 public:
  explicit Describer(const Options& o)
      : config_(loadParams(o)), orb_(config_.orb), lines_(config_.lines) {}

  cv::Mat describe(DescriptorKind kind, const cv::Mat& gray) const {
    cv::Mat descriptors;
    if (kind == DescriptorKind::kOrb) {
      std::vector<cv::KeyPoint> keypoints;
      orb_.extract(gray, keypoints, descriptors);
      return descriptors;
    }
    PinholeCamera camera;  // rectified: the image's own pixels; intrinsics only for geometry
    camera.width = gray.cols;
    camera.height = gray.rows;
    camera.fx = camera.fy = std::max(gray.cols, gray.rows);
    camera.cx = gray.cols / 2.0;
    camera.cy = gray.rows / 2.0;
    return lines_.describe(gray, lines_.detect(gray, camera));
  }

 private:
  static SystemConfig loadParams(const Options& o) {
    SystemConfig config;
    if (!o.config.empty()) config = loadConfig(o.config);
    if (o.max_features > 0) {
      config.orb.num_features = static_cast<int>(o.max_features);
      config.lines.max_lines = static_cast<int>(o.max_features);
    }
    return config;
  }

  SystemConfig config_;
  OrbExtractor orb_;
  LineExtractor lines_;
};

std::vector<cv::Mat> describeAll(const TrainingImages& images, const Describer& describer,
                                 DescriptorKind kind) {
  std::vector<cv::Mat> out;
  long descriptors = 0;
  images.forEach([&](const cv::Mat& gray, const std::string& name) {
    out.push_back(describer.describe(kind, gray));
    descriptors += out.back().rows;
    if (out.size() % 25 == 0)
      std::cout << "  images " << out.size() << ", descriptors " << descriptors << std::endl;
  });
  std::cout << "  images " << out.size() << ", descriptors " << descriptors << std::endl;
  return out;
}

// Nothing is written then: a good vocabulary in --out's place stays (it was replaced by a
// one-word file, issue #53).
void refuseTooFew(const std::vector<cv::Mat>& descriptors, const Options& o) {
  long rows = 0;
  for (const cv::Mat& d : descriptors) rows += d.rows;
  if (rows >= o.vocabulary.branching) return;
  throw std::runtime_error(o.images + " gave " + std::to_string(rows) + " descriptors in " +
                           std::to_string(descriptors.size()) +
                           " readable images, fewer than k = " +
                           std::to_string(o.vocabulary.branching) + "; " + o.out + " not written");
}

int train(const Options& o) {
  const Stopwatch total;
  const TrainingImages images(o.images, o.video_step);
  std::cout << descriptorKindName(o.vocabulary.kind) << " descriptors of " << images.files().size()
            << " files (videos: one frame in " << o.video_step << ")" << std::endl;
  const Describer describer(o);
  const std::vector<cv::Mat> descriptors = describeAll(images, describer, o.vocabulary.kind);
  std::cout << "extraction " << total.elapsedMs() / 1000.0 << " s" << std::endl;
  refuseTooFew(descriptors, o);
  const Stopwatch clustering;
  const BinaryVocabulary vocabulary = BinaryVocabulary::train(
      descriptors, o.vocabulary,
      [](const std::string& line) { std::cout << "  " << line << std::endl; });
  std::cout << "clustering " << clustering.elapsedMs() / 1000.0 << " s" << std::endl;
  vocabulary.save(o.out);
  std::cout << "wrote " << o.out << ": " << vocabulary.numNodes() << " nodes, "
            << vocabulary.numWords() << " words; total training time " << total.elapsedMs() / 1000.0
            << " s" << std::endl;
  return 0;
}

// Each row with `flips` random bits inverted (repeats allowed): another view's descriptors.
cv::Mat noisy(const cv::Mat& descriptors, int flips, std::mt19937& rng) {
  cv::Mat out = descriptors.clone();
  for (int r = 0; r < out.rows; ++r)
    for (int f = 0; f < flips; ++f) {
      const unsigned bit = rng() % (8 * out.cols);
      out.at<uint8_t>(r, bit / 8) ^= static_cast<uint8_t>(1u << (bit % 8));
    }
  return out;
}

struct FrameDescriptors {
  cv::Mat orb, lbd;
};

KeyFrameWords words(const FrameDescriptors& f, const BinaryVocabulary& orb,
                    const BinaryVocabulary& lbd) {
  KeyFrameWords w;
  orb.transform(f.orb, w.points, w.point_features, 3);
  lbd.transform(f.lbd, w.lines, w.line_features, 3);
  return w;
}

std::string msText(const std::vector<double>& ms) {
  double sum = 0.0;
  for (double v : ms) sum += v;
  std::ostringstream out;
  out << std::fixed << std::setprecision(3) << "mean " << sum / ms.size() << " ms, median "
      << median(ms) << " ms, max " << percentile(ms, 1.0) << " ms";
  return out.str();
}

int benchmark(const Options& o) {
  Stopwatch watch;
  const BinaryVocabulary orb = BinaryVocabulary::load(o.orb_vocabulary, DescriptorKind::kOrb);
  const BinaryVocabulary lbd = BinaryVocabulary::load(o.lbd_vocabulary, DescriptorKind::kLbd);
  std::cout << "loading both vocabularies: " << watch.elapsedMs() << " ms (" << orb.numWords()
            << " orb words, " << lbd.numWords() << " lbd words)" << std::endl;
  const Describer describer(o);
  std::vector<FrameDescriptors> frames;
  TrainingImages(o.images, o.video_step).forEach([&](const cv::Mat& gray, const std::string&) {
    frames.push_back({describer.describe(DescriptorKind::kOrb, gray),
                      describer.describe(DescriptorKind::kLbd, gray)});
  });
  std::mt19937 rng(1);
  BowDatabase database(orb.numWords(), lbd.numWords());
  std::vector<double> transform_ms, query_ms;
  for (long k = 0; k < o.keyframes; ++k) {
    const FrameDescriptors& f = frames[k % frames.size()];
    const FrameDescriptors copy{noisy(f.orb, 8, rng), noisy(f.lbd, 8, rng)};
    watch.restart();
    KeyFrameWords w = words(copy, orb, lbd);
    transform_ms.push_back(watch.elapsedMs());
    database.add(k, std::move(w));
  }
  long right = 0, candidates = 0;
  for (int q = 0; q < 200; ++q) {
    const size_t source = rng() % frames.size();
    const KeyFrameWords w =
        words({noisy(frames[source].orb, 8, rng), noisy(frames[source].lbd, 8, rng)}, orb, lbd);
    watch.restart();
    const std::vector<BowCandidate> found = database.query(w.points, w.lines, 10);
    query_ms.push_back(watch.elapsedMs());
    candidates += static_cast<long>(found.size());
    right += !found.empty() && static_cast<size_t>(found[0].keyframe_id) % frames.size() == source;
  }
  long points = 0, lines = 0;
  for (const FrameDescriptors& f : frames) points += f.orb.rows, lines += f.lbd.rows;
  std::cout << frames.size() << " images (mean " << points / static_cast<long>(frames.size())
            << " ORB, " << lines / static_cast<long>(frames.size()) << " LBD); " << database.size()
            << " keyframes (noisy copies, 8 of 256 bits flipped)\n"
            << "transform (orb + lbd) per keyframe: " << msText(transform_ms) << "\n"
            << "query (10 results): " << msText(query_ms) << "\n"
            << "top candidate from the query's image: " << right << " / 200" << std::endl;
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return ply_slam::runTool("ply_slam_vocabulary", kUsage, [&] {
    const Options options = parse(argc, argv);
    return options.benchmark ? benchmark(options) : train(options);
  });
}
