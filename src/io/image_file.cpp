#include "ply_slam/io/image_file.h"

#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <vector>

#include "ply_slam/io/atomic_file.h"
#include "ply_slam/io/file_writes.h"

namespace ply_slam {

void writeImageFile(const std::string& path, const cv::Mat& image) {
  // Encoded in memory and written through our checked stream: cv::imwrite reports success on
  // a full disk (a 0-byte map.pgm, issue #53).
  std::vector<uchar> bytes;
  bool encoded = false;
  try {
    encoded = cv::imencode(std::filesystem::path(path).extension().string(), image, bytes);
  } catch (const cv::Exception& e) {  // an unknown extension, a type the format cannot hold
    throw FileWriteError(path, std::string("cannot encode the image: ") + e.what());
  }
  if (!encoded) throw FileWriteError(path, "cannot encode the image");
  AtomicFile file(path, std::ios::binary);
  file.stream().write(reinterpret_cast<const char*>(bytes.data()),
                      static_cast<std::streamsize>(bytes.size()));
  file.commit();
}

}  // namespace ply_slam
