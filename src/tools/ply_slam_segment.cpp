// Runs YOLOv8-seg on a TUM folder and reports time per frame and, where the folder has
// ground-truth masks (masks/, instances.txt), the person-mask IoU:
//   ply_slam_segment --sequence DIR --model ONNX --input WxH [--classes FILE] [--every N]
//                    [--save DIR]
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <opencv2/imgproc.hpp>
#include <tuple>

#include "ply_slam/common/command_line.h"
#include "ply_slam/common/number_text.h"
#include "ply_slam/common/statistics.h"
#include "ply_slam/common/stopwatch.h"
#include "ply_slam/io/image_file.h"
#include "ply_slam/io/tum_sequence.h"
#include "ply_slam/semantic/mask_folder_segmenter.h"
#include "ply_slam/semantic/yolo_v8_seg.h"

namespace fs = std::filesystem;
using namespace ply_slam;

namespace {

const char* const kUsage =
    "usage: ply_slam_segment --sequence DIR --model ONNX --input WxH"
    " [--classes FILE] [--every N] [--save DIR]\n";

struct Options {
  std::string sequence_dir, save_dir;
  YoloOptions params;
  int every = 1;
};

void setOption(Options& o, const std::string& arg, const std::string& value) {
  if (arg == "--sequence") {
    o.sequence_dir = value;
  } else if (arg == "--model") {
    o.params.model_path = value;
  } else if (arg == "--classes") {
    o.params.class_names_path = value;
  } else if (arg == "--input") {
    const auto size = parseImageSize(value);
    if (!size) throw UsageError("--input needs WxH, e.g. 640x480, got '" + value + "'");
    std::tie(o.params.input_width, o.params.input_height) = *size;
  } else if (arg == "--every") {
    o.every = static_cast<int>(wholeNumberArgument(arg, value, 1, 100000));
  } else {
    o.save_dir = value;
  }
}

Options parse(int argc, char** argv) {
  Options o;
  CommandLine line;
  line.usage_text = kUsage;
  line.options = {"--sequence", "--model", "--classes", "--input", "--every", "--save"};
  line.on_option = [&](const std::string& arg, const std::string& value) {
    setOption(o, arg, value);
  };
  line.parse(argc, argv);
  if (o.sequence_dir.empty() || o.params.model_path.empty())
    throw UsageError("--sequence and --model are required");
  return o;
}

int run(const Options& options) {
  const std::string& sequence_dir = options.sequence_dir;
  const std::string& save_dir = options.save_dir;
  const YoloOptions& params = options.params;
  const int every = options.every;

  YoloV8Seg yolo(params);
  const TumSequence sequence(sequence_dir);
  const bool has_truth = fs::exists(fs::path(sequence_dir) / "instances.txt");
  std::unique_ptr<MaskFolderSegmenter> truth;
  if (has_truth) truth = std::make_unique<MaskFolderSegmenter>(sequence_dir);
  if (!save_dir.empty()) fs::create_directories(save_dir);

  std::vector<double> ms, ious;
  for (size_t i = 0; i < sequence.size(); i += every) {
    const RgbdImages images = sequence.load(i, 5000.0);
    Stopwatch watch;
    const auto instances = yolo.segment(images);
    ms.push_back(watch.elapsedMs());
    if (truth) {
      for (const auto& walker : truth->segment(images)) {
        if (cv::countNonZero(walker.mask) < 0.02 * walker.mask.total()) continue;
        double best = 0.0;
        for (const auto& instance : instances) {
          if (instance.class_name != walker.class_name) continue;
          const double inter = cv::countNonZero(instance.mask & walker.mask);
          const double uni = cv::countNonZero(instance.mask | walker.mask);
          best = std::max(best, inter / uni);
        }
        ious.push_back(best);
      }
    }
    if (!save_dir.empty()) {
      cv::Mat overlay = images.rgb.clone();
      for (const auto& instance : instances) {
        const cv::Scalar colour =
            instance.class_name == "person" ? cv::Scalar(0, 0, 255) : cv::Scalar(255, 160, 0);
        overlay.setTo(colour, instance.mask);
      }
      cv::addWeighted(images.rgb, 0.5, overlay, 0.5, 0, overlay);
      char name[64];
      std::snprintf(name, sizeof(name), "%.6f.png", images.stamp);
      writeImageFile((fs::path(save_dir) / name).string(), overlay);
    }
  }
  std::cout << std::fixed << std::setprecision(1) << fs::path(params.model_path).filename().string()
            << ": " << ms.size() << " frames, " << median(ms, std::nan(""))
            << " ms median per frame";
  if (truth) {
    const long missed = std::count_if(ious.begin(), ious.end(), [](double x) { return x < 0.3; });
    std::cout << std::setprecision(3) << ", person mask IoU median " << median(ious, std::nan(""))
              << " over " << ious.size() << " views (walkers > 2 % of the image), " << missed
              << " of them missed (IoU < 0.3)";
  }
  std::cout << "\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return runTool("ply_slam_segment", kUsage, [&] { return run(parse(argc, argv)); });
}
