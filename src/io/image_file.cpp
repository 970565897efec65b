#include "ply_slam/io/image_file.h"

#include <opencv2/imgcodecs.hpp>

#include "ply_slam/io/atomic_file.h"

namespace ply_slam {

void writeImageFile(const std::string& path, const cv::Mat& image) {
  // cv::imwrite returns false for most failures and throws cv::Exception for some.
  writeFileAtomically(path, [&](const std::string& temp) { return cv::imwrite(temp, image); });
}

}  // namespace ply_slam
