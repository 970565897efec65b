#include "ply_slam/io/tum_sequence.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <locale>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>
#include <stdexcept>

#include "ply_slam/io/input_file.h"
#include "ply_slam/io/tum_trajectory_file.h"

namespace ply_slam {
namespace {

namespace fs = std::filesystem;

struct StampedFile {
  double stamp = 0.0;
  std::string path;  // as written in the list file (relative to the folder)
};

// "8UC3" style name, as the error messages promise (the actual type, not just "wrong").
std::string typeName(int type) {
  static const char* kDepths[] = {"8U", "8S", "16U", "16S", "32S", "32F", "64F", "16F"};
  return std::string(kDepths[CV_MAT_DEPTH(type)]) + "C" + std::to_string(CV_MAT_CN(type));
}

// Reads the non-comment lines of a TUM list file, each split into whitespace tokens.
// Calls on_line(tokens, line_number) so that each format reports its own expectation.
template <typename OnLine>
void forEachEntry(const std::string& path, OnLine on_line) {
  refuseSpecialFile(path);  // a named pipe would block the open for ever
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot open");
  std::string line;
  int line_number = 0;
  while (std::getline(in, line)) {
    ++line_number;
    if (!line.empty() && line.back() == '\r') line.pop_back();  // files edited on Windows
    const size_t first = line.find_first_not_of(" \t");
    if (first == std::string::npos || line[first] == '#') continue;
    std::istringstream tokens_in(line);
    std::vector<std::string> tokens;
    for (std::string token; tokens_in >> token;) tokens.push_back(token);
    on_line(tokens, line_number);
  }
}

// A list file the folder must have (forEachEntry refuses one that is not a regular file).
void requireListFile(const std::string& path) {
  if (!fs::exists(path)) throw std::runtime_error(path + ": missing");
}

// Parses a stamp in the C locale: a global locale with a decimal comma must not change
// how a data set is read.
bool parseStamp(const std::string& text, double* stamp) {
  std::istringstream in(text);
  in.imbue(std::locale::classic());
  in >> *stamp;
  return !in.fail() && in.peek() == std::char_traits<char>::eof() && std::isfinite(*stamp);
}

[[noreturn]] void throwMalformed(const std::string& path, int line_number,
                                 const std::string& expected) {
  throw std::runtime_error(path + ":" + std::to_string(line_number) +
                           ": malformed line, expected '" + expected + "'");
}

// "stamp path" lists (rgb.txt, depth.txt), sorted by stamp; equal stamps make the order
// (and the association) ambiguous, so they are an error.
std::vector<StampedFile> readFileList(const std::string& path) {
  std::vector<StampedFile> files;
  forEachEntry(path, [&](const std::vector<std::string>& tokens, int line_number) {
    StampedFile file;
    if (tokens.size() != 2 || !parseStamp(tokens[0], &file.stamp)) {
      throwMalformed(path, line_number, "stamp relative/path");
    }
    file.path = tokens[1];
    files.push_back(file);
  });
  std::stable_sort(files.begin(), files.end(),
                   [](const StampedFile& a, const StampedFile& b) { return a.stamp < b.stamp; });
  for (size_t i = 1; i < files.size(); ++i) {
    if (files[i].stamp == files[i - 1].stamp) {
      std::ostringstream msg;
      msg.precision(6);
      msg << path << ": duplicate stamp " << std::fixed << files[i].stamp << " ("
          << files[i - 1].path << ", " << files[i].path << ")";
      throw std::runtime_error(msg.str());
    }
  }
  return files;
}

std::string joinPath(const std::string& folder, const std::string& relative) {
  return folder + "/" + relative;
}

}  // namespace

TumSequence::TumSequence(const std::string& folder, double max_stamp_difference) {
  folder_ = folder;
  while (folder_.size() > 1 && folder_.back() == '/') folder_.pop_back();
  if (!fs::is_directory(folder_)) {
    throw std::runtime_error(folder_ + ": TUM sequence folder missing");
  }
  const std::string rgb_list = joinPath(folder_, "rgb.txt");
  const std::string depth_list = joinPath(folder_, "depth.txt");
  const std::string associations = joinPath(folder_, "associations.txt");
  requireListFile(rgb_list);
  const std::vector<StampedFile> rgb = readFileList(rgb_list);
  if (rgb.empty()) throw std::runtime_error(rgb_list + ": lists no frames");

  if (fs::exists(associations)) {  // a named pipe or a directory there is refused
    // The data set's own pairing wins: results stay comparable with other systems.
    used_associations_file_ = true;
    forEachEntry(associations, [&](const std::vector<std::string>& tokens, int line_number) {
      RgbdRecord r;
      if (tokens.size() != 4 || !parseStamp(tokens[0], &r.rgb_stamp) ||
          !parseStamp(tokens[2], &r.depth_stamp)) {
        throwMalformed(associations, line_number, "rgb_stamp rgb_path depth_stamp depth_path");
      }
      r.rgb_path = joinPath(folder_, tokens[1]);
      r.depth_path = joinPath(folder_, tokens[3]);
      records_.push_back(r);
    });
    std::stable_sort(
        records_.begin(), records_.end(),
        [](const RgbdRecord& a, const RgbdRecord& b) { return a.rgb_stamp < b.rgb_stamp; });
    for (size_t i = 1; i < records_.size(); ++i) {
      if (records_[i].rgb_stamp == records_[i - 1].rgb_stamp) {
        throw std::runtime_error(associations + ": duplicate rgb stamp for " +
                                 records_[i].rgb_path);
      }
    }
    // rgb frames the file leaves out count as unassociated, as they would without it.
    unassociated_ = rgb.size() > records_.size() ? rgb.size() - records_.size() : 0;
    if (records_.empty()) throw std::runtime_error(associations + ": lists no frames");
  } else {
    requireListFile(depth_list);
    const std::vector<StampedFile> depth = readFileList(depth_list);
    // Nearest depth per rgb frame, not TUM's greedy one-to-one matching: a depth image may
    // serve several rgb frames, so no rgb frame is dropped just because a neighbour was
    // slightly closer to the same depth image.
    for (const StampedFile& frame : rgb) {
      auto next =
          std::lower_bound(depth.begin(), depth.end(), frame.stamp,
                           [](const StampedFile& d, double stamp) { return d.stamp < stamp; });
      auto best = depth.end();
      double best_dt = max_stamp_difference;
      if (next != depth.end() && std::abs(next->stamp - frame.stamp) <= best_dt) {
        best = next;
        best_dt = std::abs(next->stamp - frame.stamp);
      }
      if (next != depth.begin() && std::abs(std::prev(next)->stamp - frame.stamp) <= best_dt) {
        best = std::prev(next);
      }
      if (best == depth.end()) {
        ++unassociated_;
        continue;
      }
      records_.push_back(
          {frame.stamp, joinPath(folder_, frame.path), best->stamp, joinPath(folder_, best->path)});
    }
    if (records_.empty()) {
      throw std::runtime_error(folder_ + ": no rgb frame has a depth image within " +
                               std::to_string(max_stamp_difference) + " s");
    }
  }

  readGroundTruth(joinPath(folder_, "groundtruth.txt"));
}

void TumSequence::readGroundTruth(const std::string& path) {
  if (!fs::exists(path)) return;
  // The run goes on without: its outputs are written, and the summary says why there is no ATE.
  if (const auto problem = specialFileProblem(path)) {
    ground_truth_problem_ = path + ": " + *problem;
    return;
  }
  ground_truth_ = readTumTrajectory(path);
  if (ground_truth_.empty()) ground_truth_problem_ = path + ": holds no poses";
}

RgbdImages TumSequence::load(size_t i, double depth_factor) const {
  if (i >= records_.size()) {
    throw std::out_of_range(folder_ + ": frame " + std::to_string(i) + " out of range (" +
                            std::to_string(records_.size()) + " frames)");
  }
  if (!(depth_factor > 0.0)) {
    throw std::invalid_argument("TumSequence::load: depth_factor must be positive");
  }
  const RgbdRecord& r = records_[i];
  auto read = [](const std::string& path) {
    refuseSpecialFile(path);
    if (!fs::is_regular_file(path)) throw std::runtime_error(path + ": image missing");
    cv::Mat image = cv::imread(path, cv::IMREAD_UNCHANGED);
    if (image.empty()) throw std::runtime_error(path + ": image unreadable");
    return image;
  };

  RgbdImages out;
  out.stamp = r.rgb_stamp;
  out.depth_stamp = r.depth_stamp;
  cv::Mat rgb = read(r.rgb_path);
  if (rgb.depth() != CV_8U || (rgb.channels() != 3 && rgb.channels() != 4)) {
    throw std::runtime_error(r.rgb_path + ": wrong type " + typeName(rgb.type()) +
                             ", expected colour (8UC3 or 8UC4)");
  }
  if (rgb.channels() == 4) {
    cv::cvtColor(rgb, out.rgb, cv::COLOR_BGRA2BGR);
  } else {
    out.rgb = rgb;
  }

  cv::Mat depth = read(r.depth_path);
  if (depth.type() != CV_16UC1) {
    throw std::runtime_error(r.depth_path + ": wrong type " + typeName(depth.type()) +
                             ", expected 16UC1 depth");
  }
  if (depth.size() != rgb.size()) {
    std::ostringstream msg;
    msg << r.depth_path << ": size mismatch, depth " << depth.cols << "x" << depth.rows << " but "
        << r.rgb_path << " is " << rgb.cols << "x" << rgb.rows;
    throw std::runtime_error(msg.str());
  }
  // Linear scaling keeps 0 (no measurement) at 0.
  depth.convertTo(out.depth, CV_32F, 1.0 / depth_factor);
  return out;
}

}  // namespace ply_slam
