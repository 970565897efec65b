#include "ply_slam/dense/cloud_files.h"

#include <pcl/console/print.h>
#include <pcl/io/pcd_io.h>
#include <pcl/io/ply_io.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <cstring>
#include <filesystem>
#include <vector>

#include "ply_slam/io/atomic_file.h"

namespace ply_slam {
namespace {

using Point = DenseCloud::PointType;

// The bytes pcl::io::savePCDFileBinary writes (its header; each point's named fields, no
// padding), made in memory for a checked stream.
std::string pcdBytes(const DenseCloud& cloud) {
  std::string bytes = pcl::PCDWriter::generateHeader<Point>(cloud) + "DATA binary\n";
  std::vector<pcl::PCLPointField> fields;
  for (const auto& field : pcl::getFields<Point>())
    if (field.name != "_") fields.push_back(field);
  for (const Point& point : cloud)
    for (const auto& field : fields)
      bytes.append(reinterpret_cast<const char*>(&point) + field.offset,
                   field.count * pcl::getFieldSize(field.datatype));
  return bytes;
}

// What is wrong with the PLY file at `path` that should hold `points` points; "" when whole.
std::string plyProblem(const std::string& path, size_t points) {
  if (std::filesystem::file_size(path) == 0) return "the writer left it empty (disk full?)";
  pcl::PCLPointCloud2 back;
  // Quiet: PCL's reader warns of the camera element its own writer adds, at every read.
  const pcl::console::VERBOSITY_LEVEL level = pcl::console::getVerbosityLevel();
  pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);
  const int read = pcl::io::loadPLYFile(path, back);
  pcl::console::setVerbosityLevel(level);
  if (read != 0) return "the written file does not read back (disk full?)";
  if (size_t{back.width} * back.height != points)
    return "the written file holds " + std::to_string(size_t{back.width} * back.height) + " of " +
           std::to_string(points) + " points (disk full?)";
  return "";
}

}  // namespace

void writeCloudPcd(const std::string& path, const DenseCloud& cloud) {
  const std::string bytes = pcdBytes(cloud);
  AtomicFile file(path, std::ios::binary);
  file.stream().write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  file.commit();
}

void writeCloudPly(const std::string& path, const DenseCloud& cloud) {
  writeFileAtomically(
      path, [&](const std::string& temp) { return pcl::io::savePLYFileBinary(temp, cloud) == 0; },
      [&](const std::string& temp) { return plyProblem(temp, cloud.size()); });
}

}  // namespace ply_slam
