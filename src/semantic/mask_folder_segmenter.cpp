#include "ply_slam/semantic/mask_folder_segmenter.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <sstream>
#include <stdexcept>

#include "ply_slam/io/input_file.h"

namespace ply_slam {

std::map<int, std::string> readInstanceClasses(const std::string& path) {
  refuseSpecialFile(path);
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": missing (the instance id -> class list)");
  std::map<int, std::string> classes;
  int line_number = 0;
  for (std::string line; std::getline(in, line);) {
    ++line_number;
    if (line.empty() || line[0] == '#' || line.find_first_not_of(" \t\r") == std::string::npos)
      continue;
    std::istringstream fields(line);
    int id = 0;
    std::string class_name;
    if (!(fields >> id >> class_name) || id <= 0 || id > 255)
      throw std::runtime_error(path + " line " + std::to_string(line_number) +
                               ": expected \"id class_name\" with id in 1..255");
    std::replace(class_name.begin(), class_name.end(), '_', ' ');
    classes[id] = class_name;
  }
  return classes;
}

MaskFolderSegmenter::MaskFolderSegmenter(const std::string& folder)
    : folder_(folder), classes_(readInstanceClasses(folder + "/instances.txt")) {
  if (!std::filesystem::is_directory(folder + "/masks"))
    throw std::runtime_error(folder + "/masks: missing folder of instance masks");
}

std::vector<Instance> MaskFolderSegmenter::segment(const RgbdImages& images) {
  char name[64];
  std::snprintf(name, sizeof(name), "%.6f.png", images.stamp);
  const std::string path = folder_ + "/masks/" + name;
  refuseSpecialFile(path);
  if (!std::filesystem::exists(path)) throw std::runtime_error(path + ": mask missing");
  const cv::Mat ids = cv::imread(path, cv::IMREAD_UNCHANGED);
  if (ids.empty()) throw std::runtime_error(path + ": mask unreadable");
  if (ids.type() != CV_8UC1)
    throw std::runtime_error(path + ": mask must be 8-bit single channel (got " +
                             cv::typeToString(ids.type()) + ")");
  if (ids.size() != images.rgb.size())
    throw std::runtime_error(path + ": mask size differs from the rgb image");

  std::vector<Instance> instances;
  for (const auto& [id, class_name] : classes_) {
    cv::Mat mask = ids == id;
    if (cv::countNonZero(mask) == 0) continue;
    instances.push_back({id, class_name, 1.0f, mask});
  }
  return instances;
}

}  // namespace ply_slam
