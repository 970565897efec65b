#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <memory>
#include <opencv2/core.hpp>
#include <vector>

namespace ply_slam {

struct KeyFrame;

// A static 3D point landmark with the ORB descriptor it is matched by.
struct MapPoint {
  long id = 0;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  // world frame, m
  cv::Mat descriptor;                                  // 1x32 CV_8U
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();   // mean viewing direction (unit)
  // Distances at which the point can be seen at scale level 0 .. last (scale invariance).
  double min_distance = 0.0, max_distance = 0.0;
  double position_weight = 0.0;  // sum of inverse variances fused into `position`
  struct Observer {
    KeyFrame* keyframe;
    size_t index;  // keypoint index in that keyframe
  };
  std::vector<Observer> observers;  // keyframes that observe it
  int visible = 0;                  // frames in whose frustum it projected
  int found = 0;                    // frames in which it was matched as an inlier
  long first_keyframe_id = 0;
  bool bad = false;
  std::shared_ptr<MapPoint> replaced_by;  // set when merged into a duplicate of itself

  int observations() const { return static_cast<int>(observers.size()); }
  bool seenBy(const KeyFrame* keyframe) const;  // among the observers
  double foundRatio() const { return visible > 0 ? static_cast<double>(found) / visible : 1.0; }
  // Pyramid level at which a point `distance` away is expected to appear.
  int predictLevel(double distance, double log_scale, int num_levels) const;
  // Fuses another depth measurement of the point (world frame) with inverse variance w.
  void fuse(const Eigen::Vector3d& measured, double weight);
  // Moves the point rigidly with the world: position and viewing direction.
  void moveBy(const Eigen::Isometry3d& move);
};

}  // namespace ply_slam
