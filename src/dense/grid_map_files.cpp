#include "ply_slam/dense/grid_map_files.h"

#include <cmath>
#include <filesystem>
#include <locale>
#include <sstream>

#include "ply_slam/io/atomic_file.h"
#include "ply_slam/io/file_writes.h"
#include "ply_slam/io/image_file.h"

namespace ply_slam {

cv::Mat gridMapImage(const OccupancyGrid& grid) {
  cv::Mat image(grid.height(), grid.width(), CV_8UC1, cv::Scalar(205));
  for (int j = 0; j < grid.height(); ++j)
    for (int i = 0; i < grid.width(); ++i) {
      const std::int8_t cell = grid.at(i, j);
      if (cell == OccupancyGrid::kUnknown) continue;
      image.at<std::uint8_t>(grid.height() - 1 - j, i) = cell == OccupancyGrid::kFree ? 254 : 0;
    }
  return image;
}

std::vector<std::string> writeGridMap(const std::string& folder, const OccupancyGrid& grid,
                                      const Eigen::Isometry3d& T_frame_floor) {
  namespace fs = std::filesystem;
  fs::create_directories(folder);
  const std::string pgm = (fs::path(folder) / "map.pgm").string();
  const std::string yaml = (fs::path(folder) / "map.yaml").string();
  // An empty grid still makes a loadable map: one unknown cell.
  const cv::Mat image = grid.width() > 0 ? gridMapImage(grid) : cv::Mat(1, 1, CV_8UC1, 205);
  FileWrites files;  // each tried: a map.pgm that fails does not keep map.yaml off the disk
  files.attempt([&] { writeImageFile(pgm, image); });

  const Eigen::Isometry3d corner = grid.corner(T_frame_floor);
  const double yaw = std::atan2(corner(1, 0), corner(0, 0));
  std::ostringstream out;
  out.imbue(std::locale::classic());
  out.precision(9);
  out << "image: map.pgm\n"
      << "resolution: " << grid.resolution() << "\n"
      << "origin: [" << corner.translation().x() << ", " << corner.translation().y() << ", " << yaw
      << "]\n"
      << "negate: 0\n"
      << "occupied_thresh: 0.65\n"
      << "free_thresh: 0.196\n";
  files.attempt([&] { writeTextFileAtomically(yaml, out.str()); });
  files.throwFailures();
  return {pgm, yaml};
}

}  // namespace ply_slam
