#pragma once

#include <opencv2/core.hpp>
#include <string>

namespace ply_slam {

// Encoded as the extension says (cv::imencode) and written through AtomicFile: the image is whole
// or absent; a failure throws an error naming the file.
void writeImageFile(const std::string& path, const cv::Mat& image);

}  // namespace ply_slam
