#pragma once

#include <functional>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace ply_slam {

// The images a vocabulary is trained on, named by one path: a folder (every .png/.jpg/.jpeg
// and .avi below it, recursively, in name order), a video file, or a text file with one
// image or video path per line (relative paths from the list's folder). Videos give every
// `video_step`-th frame: neighbouring frames would repeat the same words.
class TrainingImages {
 public:
  using Visit = std::function<void(const cv::Mat& gray, const std::string& name)>;

  // Throws std::runtime_error when `path` does not exist or names no usable file.
  TrainingImages(const std::string& path, int video_step);

  const std::vector<std::string>& files() const { return files_; }
  // Calls `visit` with each image (grey) in order; unreadable files are reported and skipped.
  void forEach(const Visit& visit) const;

  static bool isImage(const std::string& path);
  static bool isVideo(const std::string& path);

 private:
  void visitVideo(const std::string& path, const Visit& visit) const;

  std::vector<std::string> files_;
  int video_step_;
};

}  // namespace ply_slam
