#include "ply_slam/dense/grid_map_files.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <locale>
#include <opencv2/imgcodecs.hpp>
#include <stdexcept>

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
  if (!cv::imwrite(pgm, image)) throw std::runtime_error("cannot write " + pgm);

  const Eigen::Vector3d corner =
      T_frame_floor * Eigen::Vector3d(grid.origin().x(), grid.origin().y(), 0.0);
  const double yaw = std::atan2(T_frame_floor(1, 0), T_frame_floor(0, 0));
  std::ofstream out(yaml);
  out.imbue(std::locale::classic());
  out.precision(9);
  out << "image: map.pgm\n"
      << "resolution: " << grid.resolution() << "\n"
      << "origin: [" << corner.x() << ", " << corner.y() << ", " << yaw << "]\n"
      << "negate: 0\n"
      << "occupied_thresh: 0.65\n"
      << "free_thresh: 0.196\n";
  if (!out) throw std::runtime_error("cannot write " + yaml);
  return {pgm, yaml};
}

}  // namespace ply_slam
