#pragma once

#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <vector>

namespace ply_slam {

// Where and how a hand-held camera moves in a scene.
struct CameraPathSpec {
  Eigen::Vector3d centre = Eigen::Vector3d(0.0, 0.0, 1.4);  // mean position (world, m)
  double yaw = 0.0;    // rad, mean viewing direction about world z, from +x
  double pitch = 0.0;  // rad, positive looks up
  Eigen::Vector3d drift_velocity = Eigen::Vector3d::Zero();  // m/s, walking along
  double max_drift = 0.0;  // m, cap on the whole drift (keeps the camera in the room)
  Eigen::Vector3d position_extent = Eigen::Vector3d(0.3, 0.3, 0.1);  // max |offset| per axis
  Eigen::Vector3d angle_extent = Eigen::Vector3d(0.4, 0.15, 0.08);   // rad: yaw, pitch, roll
  double linear_speed = 0.3;                                         // m/s, mean
  double angular_speed = 0.524;                                      // rad/s, mean (30 deg/s)
};

// Smooth hand-held motion: the mean pose plus, per axis of position and of yaw / pitch /
// roll, a sum of sinusoids with seeded frequencies and phases, scaled so that the mean speeds
// match the spec (within the extents). With `loop` every frequency is a multiple of the
// sequence's period, so the last frame's pose equals the first's.
class CameraPath {
 public:
  CameraPath(const CameraPathSpec& spec, int frames, double fps, bool loop, uint64_t seed);

  // T_wc at time t (s): camera x right, y down, z forward.
  Eigen::Isometry3d pose(double t) const;
  Eigen::Isometry3d poseAtFrame(int i) const { return pose(i / fps_); }

  int frames() const { return frames_; }
  double fps() const { return fps_; }
  // Mean speeds over the frames, measured from consecutive poses.
  double meanLinearSpeed() const;
  double meanAngularSpeed() const;  // rad/s

 private:
  struct Wave {
    double amplitude, omega, phase;
  };
  Eigen::Vector3d offsetPosition(double t) const;
  Eigen::Vector3d offsetAngles(double t) const;
  Eigen::Vector3d drift(double t) const;
  static Eigen::Isometry3d poseFrom(const Eigen::Vector3d& position, double yaw, double pitch,
                                    double roll);

  CameraPathSpec spec_;
  int frames_;
  double fps_;
  bool loop_;
  double duration_;                         // s, from the first to the last frame
  std::array<std::vector<Wave>, 6> waves_;  // x y z yaw pitch roll
  double position_scale_ = 1.0, angle_scale_ = 1.0;
};

}  // namespace ply_slam
