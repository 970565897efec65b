#include "ply_slam/loop/training_images.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>
#include <stdexcept>

#include "ply_slam/io/input_file.h"

namespace fs = std::filesystem;

namespace ply_slam {

namespace {

std::string lowerExtension(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

std::vector<std::string> folderFiles(const std::string& dir) {
  std::vector<std::string> files;
  for (const auto& entry : fs::recursive_directory_iterator(dir)) {
    const std::string p = entry.path().string();
    if (entry.is_regular_file() && (TrainingImages::isImage(p) || TrainingImages::isVideo(p)))
      files.push_back(p);
  }
  std::sort(files.begin(), files.end());
  return files;
}

std::vector<std::string> listFiles(const std::string& list) {
  if (const auto problem = specialFileProblem(list))
    throw std::runtime_error("image list " + list + " " + *problem);
  std::ifstream in(list);
  if (!in) throw std::runtime_error("image list " + list + " cannot be read");
  const fs::path base = fs::path(list).parent_path();
  std::vector<std::string> files;
  for (std::string line; std::getline(in, line);) {
    line.erase(line.find_last_not_of(" \t\r") + 1);
    if (line.empty() || line[0] == '#') continue;
    const fs::path p(line);
    files.push_back(p.is_absolute() ? line : (base / p).string());
  }
  return files;
}

}  // namespace

bool TrainingImages::isImage(const std::string& path) {
  const std::string ext = lowerExtension(path);
  return ext == ".png" || ext == ".jpg" || ext == ".jpeg";
}

bool TrainingImages::isVideo(const std::string& path) { return lowerExtension(path) == ".avi"; }

TrainingImages::TrainingImages(const std::string& path, int video_step)
    : video_step_(std::max(1, video_step)) {
  if (!fs::exists(path)) throw std::runtime_error("training images: " + path + " does not exist");
  if (fs::is_directory(path))
    files_ = folderFiles(path);
  else if (isImage(path) || isVideo(path))
    files_ = {path};
  else
    files_ = listFiles(path);
  if (files_.empty()) throw std::runtime_error("training images: no image or video in " + path);
}

void TrainingImages::visitVideo(const std::string& path, const Visit& visit) const {
  cv::VideoCapture video(path);
  if (!video.isOpened()) {
    std::cerr << "skipped (cannot open video): " << path << "\n";
    return;
  }
  cv::Mat frame, gray;
  for (int i = 0; video.read(frame); ++i) {
    if (i % video_step_ != 0 || frame.empty()) continue;
    cv::cvtColor(frame, gray, cv::COLOR_BGR2GRAY);
    visit(gray, path + "#" + std::to_string(i));
  }
}

void TrainingImages::forEach(const Visit& visit) const {
  for (const std::string& file : files_) {
    if (isVideo(file)) {
      visitVideo(file, visit);
      continue;
    }
    const auto problem = specialFileProblem(file);
    const cv::Mat gray = problem ? cv::Mat() : cv::imread(file, cv::IMREAD_GRAYSCALE);
    if (gray.empty())
      std::cerr << "skipped (" << problem.value_or("unreadable image") << "): " << file << "\n";
    else
      visit(gray, file);
  }
}

}  // namespace ply_slam
