#include "ply_slam/map/world_in_map_file.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "ply_slam/io/atomic_file.h"
#include "ply_slam/io/input_file.h"

namespace ply_slam {

void WorldInMapFile::write(const std::string& path, const Eigen::Isometry3d& T_map_world) {
  const Eigen::Vector3d t = T_map_world.translation();
  const Eigen::Quaterniond q(T_map_world.linear());
  std::ostringstream text;
  text.precision(17);
  text << "# the SLAM world in the map frame: x y z qx qy qz qw\n"
       << t.x() << ' ' << t.y() << ' ' << t.z() << ' ' << q.x() << ' ' << q.y() << ' ' << q.z()
       << ' ' << q.w() << '\n';
  writeTextFileAtomically(path, text.str());
}

std::optional<Eigen::Isometry3d> WorldInMapFile::read(const std::string& path) {
  if (!std::filesystem::exists(path)) return std::nullopt;
  refuseSpecialFile(path);
  std::ifstream in(path);
  std::string line;
  while (in && std::getline(in, line) && (line.empty() || line[0] == '#')) {
  }
  std::istringstream values(line);
  double v[7];
  for (double& x : v)
    if (!(values >> x) || !std::isfinite(x))
      throw std::runtime_error(path + ": not a pose (x y z qx qy qz qw expected)");
  Eigen::Quaterniond q(v[6], v[3], v[4], v[5]);
  if (std::abs(q.norm() - 1.0) > 1e-6)
    throw std::runtime_error(path + ": the rotation is not a unit quaternion");
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = q.normalized().toRotationMatrix();
  T.translation() = Eigen::Vector3d(v[0], v[1], v[2]);
  return T;
}

}  // namespace ply_slam
