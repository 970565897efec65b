// Runs YOLOv8-seg on a TUM folder and reports time per frame and, where the folder has
// ground-truth masks (masks/, instances.txt), the person-mask IoU:
//   ply_slam_segment --sequence DIR --model ONNX --input WxH [--classes FILE] [--every N]
//                    [--save DIR]
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "ply_slam/common/number_text.h"
#include "ply_slam/common/statistics.h"
#include "ply_slam/common/stopwatch.h"
#include "ply_slam/io/tum_sequence.h"
#include "ply_slam/semantic/mask_folder_segmenter.h"
#include "ply_slam/semantic/yolo_v8_seg.h"

namespace fs = std::filesystem;
using namespace ply_slam;

namespace {

[[noreturn]] void usage(const std::string& error) {
  std::cerr << "ply_slam_segment: " << error << "\n"
            << "usage: ply_slam_segment --sequence DIR --model ONNX --input WxH"
               " [--classes FILE] [--every N] [--save DIR]\n";
  std::exit(2);
}

}  // namespace

int main(int argc, char** argv) {
  std::string sequence_dir, save_dir;
  YoloParams params;
  int every = 1;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (i + 1 >= argc) usage("missing value after " + arg);
    const std::string value = argv[++i];
    if (arg == "--sequence") {
      sequence_dir = value;
    } else if (arg == "--model") {
      params.model_path = value;
    } else if (arg == "--classes") {
      params.class_names_path = value;
    } else if (arg == "--input") {
      if (std::sscanf(value.c_str(), "%dx%d", &params.input_width, &params.input_height) != 2 ||
          params.input_width <= 0 || params.input_height <= 0)
        usage("--input needs WxH, e.g. 640x480");
    } else if (arg == "--every") {
      const std::optional<long> n = parseWholeNumber(value, 1, 100000);
      if (!n) usage("--every needs a whole number in [1, 100000], got '" + value + "'");
      every = static_cast<int>(*n);
    } else if (arg == "--save") {
      save_dir = value;
    } else {
      usage("unknown option " + arg);
    }
  }
  if (sequence_dir.empty() || params.model_path.empty())
    usage("--sequence and --model are required");

  try {
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
        cv::imwrite((fs::path(save_dir) / name).string(), overlay);
      }
    }
    std::cout << std::fixed << std::setprecision(1)
              << fs::path(params.model_path).filename().string() << ": " << ms.size() << " frames, "
              << upperMedian(ms, std::nan("")) << " ms median per frame";
    if (truth) {
      const long missed = std::count_if(ious.begin(), ious.end(), [](double x) { return x < 0.3; });
      std::cout << std::setprecision(3) << ", person mask IoU median "
                << upperMedian(ious, std::nan("")) << " over " << ious.size()
                << " views (walkers > 2 % of the image), " << missed
                << " of them missed (IoU < 0.3)";
    }
    std::cout << "\n";
  } catch (const std::exception& e) {
    std::cerr << "ply_slam_segment: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
