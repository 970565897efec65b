#include "ply_slam/io/tum_trajectory_file.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "ply_slam/io/atomic_file.h"
#include "ply_slam/io/input_file.h"

namespace ply_slam {
namespace {

constexpr size_t kFieldsPerLine = 8;  // stamp tx ty tz qx qy qz qw
// No trajectory reaches a million kilometres; coordinates near the largest double overflow
// every sum of squares the metrics take.
constexpr double kMaxCoordinate = 1e9;  // m

std::runtime_error lineError(const std::string& path, size_t line_number, const std::string& what,
                             const std::string& line) {
  // Long lines are cut so that a binary file passed by mistake keeps the message readable.
  const std::string shown = line.size() > 120 ? line.substr(0, 120) + "..." : line;
  std::ostringstream msg;
  msg << "trajectory file '" << path << "' line " << line_number << ": " << what << " (line: \""
      << shown << "\")";
  return std::runtime_error(msg.str());
}

// strtod with an end-pointer check rejects partial numbers such as "1.2abc"; "nan" and "inf"
// parse, so non-finite values are rejected explicitly.
bool parseFiniteDouble(const std::string& token, double* value) {
  errno = 0;
  char* end = nullptr;
  const double parsed = std::strtod(token.c_str(), &end);
  if (end == token.c_str() || *end != '\0' || errno == ERANGE || !std::isfinite(parsed)) {
    return false;
  }
  *value = parsed;
  return true;
}

}  // namespace

Trajectory readTumTrajectory(const std::string& path) {
  if (const auto problem = specialFileProblem(path))
    throw std::runtime_error("trajectory file '" + path + "' " + *problem);
  std::ifstream in(path);
  if (!in) {
    throw std::runtime_error("cannot open trajectory file '" + path + "'");
  }
  Trajectory trajectory;
  std::string line;
  size_t line_number = 0;
  while (std::getline(in, line)) {
    ++line_number;
    // TUM's own tools accept commas and tabs as separators; so do we.
    std::string normalized = line;
    for (char& c : normalized) {
      if (c == ',' || c == '\t' || c == '\r') c = ' ';
    }
    const size_t first = normalized.find_first_not_of(' ');
    if (first == std::string::npos || normalized[first] == '#') continue;

    std::istringstream tokens(normalized);
    std::vector<std::string> fields;
    std::string token;
    while (tokens >> token) fields.push_back(token);
    if (fields.size() != kFieldsPerLine) {
      throw lineError(
          path, line_number,
          "expected 8 fields 'stamp tx ty tz qx qy qz qw', got " + std::to_string(fields.size()),
          line);
    }
    double v[kFieldsPerLine];
    for (size_t k = 0; k < kFieldsPerLine; ++k) {
      if (!parseFiniteDouble(fields[k], &v[k])) {
        throw lineError(
            path, line_number,
            "field " + std::to_string(k + 1) + " '" + fields[k] + "' is not a finite number", line);
      }
    }
    for (size_t k = 1; k <= 3; ++k)
      if (std::abs(v[k]) > kMaxCoordinate)
        throw lineError(path, line_number,
                        "field " + std::to_string(k + 1) + " '" + fields[k] +
                            "' is beyond +-1e9 m, not a position",
                        line);
    // Eigen's constructor order is (w, x, y, z); the file stores qx qy qz qw.
    Eigen::Quaterniond q(v[7], v[4], v[5], v[6]);
    if (q.norm() < 1e-6) {
      throw lineError(path, line_number, "quaternion has zero norm", line);
    }
    StampedPose pose;
    pose.stamp = v[0];
    pose.T_wc.linear() = q.normalized().toRotationMatrix();
    pose.T_wc.translation() = Eigen::Vector3d(v[1], v[2], v[3]);
    trajectory.push_back(pose);
  }
  if (in.bad()) {
    throw std::runtime_error("error while reading trajectory file '" + path + "'");
  }
  return trajectory;
}

void writeTumTrajectory(const std::string& path, const Trajectory& trajectory) {
  AtomicFile file(path);
  std::ostream& out = file.stream();
  out << "# timestamp tx ty tz qx qy qz qw\n";
  for (const StampedPose& pose : trajectory) {
    Eigen::Quaterniond q(pose.T_wc.linear());
    q.normalize();
    // q and -q are the same rotation; a non-negative w keeps the output deterministic.
    if (q.w() < 0.0) q.coeffs() *= -1.0;
    const Eigen::Vector3d t = pose.T_wc.translation();
    out << std::fixed << std::setprecision(6) << pose.stamp << std::setprecision(7) << ' ' << t.x()
        << ' ' << t.y() << ' ' << t.z() << ' ' << q.x() << ' ' << q.y() << ' ' << q.z() << ' '
        << q.w() << '\n';
  }
  file.commit();
}

}  // namespace ply_slam
