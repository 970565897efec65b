#include "ply_slam/map/map_value_check.h"

#include <cmath>
#include <sstream>

#include "ply_slam/common/rotation_check.h"

namespace ply_slam {
namespace {

bool finite(double v) { return std::isfinite(v); }

bool usableCoordinates(const Eigen::Vector3d& v) {
  return v.allFinite() && v.cwiseAbs().maxCoeff() <= kMaxMapCoordinate;
}

// Empty when T is a rigid motion: finite, within bounds, R orthonormal with det +1.
std::string poseProblem(const Eigen::Isometry3d& T) {
  if (!T.matrix().allFinite()) return "a pose that is not finite";
  if (!usableCoordinates(T.translation())) return "a position beyond +-1e9 m";
  if (!isRotationMatrix(T.linear())) return "a rotation that is not a rotation matrix";
  return "";
}

std::string keyPointProblem(const FrameFeatures& f) {
  for (size_t i = 0; i < f.keypoints.size(); ++i) {
    const cv::KeyPoint& k = f.keypoints[i];
    const bool ok = finite(k.pt.x) && finite(k.pt.y) && finite(k.size) && k.size >= 0 &&
                    finite(k.angle) && finite(k.response) && f.rectified[i].allFinite() &&
                    f.undistorted[i].allFinite() && finite(f.depth[i]) && f.depth[i] >= 0;
    if (!ok)
      return "keypoint " + std::to_string(i) +
             " has a value that is not finite or a negative size or depth";
  }
  return "";
}

std::string keyFrameProblem(const KeyFrame& kf) {
  const std::string name = "keyframe " + std::to_string(kf.id) + " ";
  if (!finite(kf.stamp)) return name + "has a stamp that is not finite";
  if (const std::string p = poseProblem(kf.T_cw); !p.empty()) return name + "has " + p;
  if (const std::string p = keyPointProblem(kf.features); !p.empty()) return name + p;
  return "";
}

std::string pointProblem(const MapPoint& p) {
  const bool ok = usableCoordinates(p.position) && p.normal.allFinite() && finite(p.min_distance) &&
                  finite(p.max_distance) && p.min_distance >= 0 && p.max_distance >= 0 &&
                  finite(p.position_weight) && p.position_weight >= 0;
  return ok ? ""
            : "point " + std::to_string(p.id) +
                  " has a position beyond +-1e9 m or a value that is not finite or negative";
}

std::string lineProblem(const MapLine& l) {
  const bool ok = usableCoordinates(l.start) && usableCoordinates(l.end) &&
                  finite(l.start_weight) && finite(l.end_weight) && l.start_weight >= 0 &&
                  l.end_weight >= 0;
  return ok ? ""
            : "line " + std::to_string(l.id) +
                  " has an end beyond +-1e9 m or a value that is not finite or negative";
}

std::string placeProblem(long id, const KeyFramePlace& place) {
  for (const InstanceBox& b : place.instances)
    if (!finite(b.box.x) || !finite(b.box.y) || !finite(b.box.width) || !finite(b.box.height))
      return "keyframe " + std::to_string(id) + "'s place record has a box that is not finite";
  return "";
}

}  // namespace

std::string findMapValueProblem(const MapFileContents& map) {
  for (const auto& kf : map.keyframes)
    if (std::string p = keyFrameProblem(*kf); !p.empty()) return p;
  for (const auto& point : map.points)
    if (std::string p = pointProblem(*point); !p.empty()) return p;
  for (const auto& line : map.lines)
    if (std::string p = lineProblem(*line); !p.empty()) return p;
  for (const auto& [id, place] : map.places)
    if (std::string p = placeProblem(id, place); !p.empty()) return p;
  return "";
}

}  // namespace ply_slam
